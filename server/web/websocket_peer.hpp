// The JSON-RPC API over a WebSocket (Boost.Beast): one text message per request or batch, one per
// response or notification, with the limits of every connection (server/rpc/connection.hpp). A
// message longer than max_line_bytes gets error -32600 and the connection closes (code 1009); a
// binary message gets error -32600 and the connection stays.
#pragma once

#include <memory>
#include <string>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>

#include "server/rpc/connection.hpp"

namespace fnet::web {

// `Stream`: boost::beast::tcp_stream (ws) or a TLS stream over one (wss), its handshake done.
template <class Stream>
class WebSocketPeer final : public rpc::Connection {
 public:
  // The upgrade was admitted (http_access.hpp): the connection has presented the token `access`
  // asks for, if any.
  WebSocketPeer(Stream stream, rpc::Strand strand, const rpc::ServerLimits& limits, const rpc::Handler& handler,
                const rpc::Access& access, std::function<void()> on_end);
  // Completes the opening handshake that `upgrade` asked for, then reads.
  void accept(boost::beast::http::request<boost::beast::http::string_body> upgrade);

 private:
  std::shared_ptr<WebSocketPeer> self() { return std::static_pointer_cast<WebSocketPeer>(shared_from_this()); }
  void read_next() override;
  void write(const std::string& text) override;
  bool is_open() const override;
  bool partial_input() const override { return input_.size() > 0; }
  void finish() override;
  void close_transport() override;

  boost::beast::websocket::stream<Stream> ws_;
  boost::beast::flat_buffer input_;
  boost::beast::websocket::close_code close_code_ = boost::beast::websocket::close_code::normal;
};

}  // namespace fnet::web
