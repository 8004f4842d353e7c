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
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>

#include "proto/json_rpc.hpp"
#include "server/rpc/connection.hpp"
#include "server/rpc/listener.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::rpc {

// One TCP connection: newline-delimited requests in, responses and notifications out.
class TcpPeer final : public Connection {
 public:
  TcpPeer(boost::asio::ip::tcp::socket socket, Strand strand, const ServerLimits& limits, const Handler& handler,
          const Access& access, std::function<void()> on_end);

 private:
  std::shared_ptr<TcpPeer> self() { return std::static_pointer_cast<TcpPeer>(shared_from_this()); }
  void read_next() override;
  void write(const std::string& text) override;
  bool is_open() const override { return socket_.is_open(); }
  bool partial_input() const override { return input_.size() > 0; }
  void finish() override;
  void close_transport() override;
  void drain(const std::shared_ptr<boost::asio::steady_timer>& timer);

  boost::asio::ip::tcp::socket socket_;
  boost::asio::streambuf input_;
  bool first_line_ = true;
};

class Server {
 public:
  // Binds to `address`:`port` (port 0 picks a free one) and starts accepting; throws
  // std::runtime_error naming address:port when it cannot (the port taken, say). Beyond
  // max_connections a connection gets an error -32004 line and is closed.
  Server(boost::asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
         ServerLimits limits = {}, Access access = {});
  unsigned short port() const { return listener_.port(); }
  std::size_t connections() const { return listener_.connections(); }
  void stop() { listener_.stop(); }

 private:
  Handler handler_;
  ServerLimits limits_;
  Access access_;
  Listener listener_;
};

}  // namespace fnet::rpc
