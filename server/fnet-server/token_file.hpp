// The token fnet-server makes for itself when it listens beyond loopback and was given none.
#pragma once

#include <string>

namespace fnet::server {

// The token in `path`: made there when the file does not exist (43 characters of A-Z a-z 0-9 - _,
// 256 bits from /dev/urandom; the file created with O_EXCL, mode 0600, before any byte of the
// token is written), else read from it, refused when anyone but its owner may read or write it.
// Throws std::runtime_error naming the file and what failed.
std::string ensure_token_file(const std::string& path);

}  // namespace fnet::server
