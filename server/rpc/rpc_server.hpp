// Newline-delimited JSON-RPC 2.0 over TCP (Boost.Asio). One request per line, one response per
// line, matched by id (a heavy call may be answered after later ones); handlers may also push
// notifications to their connection at any time, from any thread. The bounds on what a client can
// make the server hold are those of every connection (connection.hpp) plus the line length and
// the number of connections.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>

#include "proto/json_rpc.hpp"
#include "server/rpc/connection.hpp"
#include "server/rpc/listener.hpp"
#include "server/rpc/peer.hpp"
#include "server/rpc/tls_context.hpp"

namespace fnet::rpc {

// One TCP connection: newline-delimited requests in, responses and notifications out, over
// `Stream`: a plain tcp::socket, or TLS (TlsStream) whose handshake must end within the
// connection's first_request_timeout, else the connection is closed and its slot freed.
template <class Stream>
class LinePeer final : public Connection {
 public:
  LinePeer(Stream stream, Strand strand, const ServerLimits& limits, const Handler& handler, const Access& access,
           std::function<void()> on_end);
  // For TLS: the server's handshake, then start(); a failed or late handshake closes the socket.
  void handshake_then_start();

 private:
  std::shared_ptr<LinePeer> self() { return std::static_pointer_cast<LinePeer>(shared_from_this()); }
  void read_next() override;
  void write(const std::string& text) override;
  bool is_open() const override { return socket().is_open(); }
  bool partial_input() const override { return input_.size() > 0; }
  void finish() override;
  void close_transport() override;
  void drain(const std::shared_ptr<boost::asio::steady_timer>& timer);
  boost::asio::ip::tcp::socket& socket() {
    if constexpr (std::is_same_v<Stream, boost::asio::ip::tcp::socket>)
      return stream_;
    else
      return stream_.next_layer();
  }
  const boost::asio::ip::tcp::socket& socket() const { return const_cast<LinePeer*>(this)->socket(); }

  Stream stream_;
  boost::asio::streambuf input_;
  bool first_line_ = true;
};

using TlsStream = boost::asio::ssl::stream<boost::asio::ip::tcp::socket>;
using TcpPeer = LinePeer<boost::asio::ip::tcp::socket>;
using TlsPeer = LinePeer<TlsStream>;

class Server {
 public:
  // Binds to `address`:`port` (port 0 picks a free one) and starts accepting; throws
  // std::runtime_error naming address:port when it cannot (the port taken, say). Beyond
  // max_connections a connection gets an error -32004 line and is closed (without a word, with
  // TLS). With `tls`, every connection speaks TLS.
  Server(boost::asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
         ServerLimits limits = {}, Access access = {}, TlsContext tls = nullptr);
  unsigned short port() const { return listener_.port(); }
  std::size_t connections() const { return listener_.connections(); }
  void stop() { listener_.stop(); }

 private:
  Handler handler_;
  ServerLimits limits_;
  Access access_;
  TlsContext tls_;
  Listener listener_;
};

}  // namespace fnet::rpc
