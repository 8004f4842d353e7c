// TLS for the API's transports (the TCP JSON-RPC port and the dashboard): a server context made
// from a certificate chain and its private key, both PEM files. TLS 1.2 or later only.
#pragma once

#include <memory>
#include <string>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio/ssl/context.hpp>

namespace fnet::rpc {

// Shared by every connection of the servers that use it; empty (null) where TLS is off.
using TlsContext = std::shared_ptr<boost::asio::ssl::context>;

// Loads `cert_file` (the certificate, then any intermediates) and `key_file`; throws
// std::runtime_error naming the file that cannot be read or the key that does not match.
TlsContext make_server_tls(const std::string& cert_file, const std::string& key_file);

}  // namespace fnet::rpc
