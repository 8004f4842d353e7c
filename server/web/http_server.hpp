// fnet-server's dashboard over HTTP (Boost.Beast): the page and its scripts (web_assets.hpp) and,
// at kRpcPath, a WebSocket carrying the JSON-RPC API (websocket_peer.hpp) through the same
// Handler as the TCP API. Connections (HTTP and WebSocket together) are bounded as the API's
// are; beyond the bound a connection gets 503 and is closed. With a TLS context, https and wss.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>

#include "server/rpc/connection.hpp"
#include "server/rpc/listener.hpp"
#include "server/rpc/peer.hpp"
#include "server/rpc/tls_context.hpp"

namespace fnet::web {

inline constexpr const char* kRpcPath = "/rpc";

class HttpServer {
 public:
  // Binds to `address`:`port` (port 0 picks a free one) and starts accepting; throws
  // std::runtime_error naming address:port when it cannot. With `tls`, every connection speaks
  // TLS (beyond the bound, such a connection is closed without a word).
  HttpServer(boost::asio::io_context& io, const std::string& address, unsigned short port, rpc::Handler handler,
             rpc::ServerLimits limits = {}, rpc::Access access = {}, rpc::TlsContext tls = nullptr);
  unsigned short port() const { return listener_.port(); }
  std::size_t connections() const { return listener_.connections(); }
  void stop() { listener_.stop(); }

 private:
  rpc::Handler handler_;
  rpc::ServerLimits limits_;
  rpc::Access access_;
  rpc::TlsContext tls_;
  rpc::Listener listener_;
};

}  // namespace fnet::web
