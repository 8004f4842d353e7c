// Who may use fnet-server's API and dashboard: anyone who can connect to its address (loopback,
// by default), or, with a token, only whoever presents it. A token is required to listen on any
// other address (fnet-server --token-file); it is compared in constant time.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace fnet::rpc {

inline constexpr std::size_t kMinTokenLength = 16;

struct Access {
  std::string token;  // empty: no token is asked for
  bool required() const { return !token.empty(); }
  // True when no token is required or `given` is the token.
  bool admits(std::string_view given) const;
};

// Compares in a time that depends on the lengths only, never on where the texts first differ.
bool same_secret(std::string_view secret, std::string_view given);

// The token held in `path`: its text without the line end; at least kMinTokenLength characters
// of A-Z a-z 0-9 . _ ~ - (so that it travels in a URL and a cookie as it is). Throws
// std::runtime_error naming the file and what is wrong.
std::string read_token_file(const std::string& path);

// Whether `address` (an IP address) is a loopback address (127.0.0.0/8, ::1).
bool is_loopback(const std::string& address);

}  // namespace fnet::rpc
