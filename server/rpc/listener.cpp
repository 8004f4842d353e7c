#include "server/rpc/listener.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>

namespace fnet::rpc {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace {

tcp::acceptor listen_on(asio::io_context& io, const std::string& address, unsigned short port) {
  tcp::acceptor acceptor(io);
  boost::system::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(address, ec);
  if (ec) throw std::runtime_error("cannot listen on '" + address + "': not an IP address");
  const tcp::endpoint endpoint(ip, port);
  // Whoever owns the port must be named: a user meeting "address in use" has to find it.
  const auto fail = [&](const char* step) {
    throw std::runtime_error("cannot listen on " + address + ":" + std::to_string(port) + ": " + step + ": " +
                             ec.message());
  };
  // (Each call then a test of ec: newer Boost returns void from the error_code overloads.)
  acceptor.open(endpoint.protocol(), ec);
  if (ec) fail("open");
  acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  if (ec) fail("setsockopt");
  acceptor.bind(endpoint, ec);
  if (ec) fail("bind");
  acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) fail("listen");
  return acceptor;
}

}  // namespace

Listener::Listener(asio::io_context& io, const std::string& address, unsigned short port, std::size_t max_connections,
                   std::string refusal, Start start)
    : io_(io),
      acceptor_(listen_on(io, address, port)),
      max_connections_(max_connections),
      refusal_(std::move(refusal)),
      start_(std::move(start)),
      retry_(io) {
  accept_next();
}

unsigned short Listener::port() const { return acceptor_.local_endpoint().port(); }

void Listener::stop() {
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  retry_.cancel();
}

void Listener::accept_later(const boost::system::error_code& why) {
  constexpr std::chrono::milliseconds kFirst{50}, kLongest{1000};
  if (backoff_.count() == 0)
    std::cerr << "fnet-server: cannot accept a connection on port " << port() << ": " << why.message()
              << "; retrying every second at most until it can\n";
  backoff_ = std::clamp(backoff_ * 2, kFirst, kLongest);
  retry_.expires_after(backoff_);
  retry_.async_wait([this](boost::system::error_code ec) {
    if (!ec && acceptor_.is_open()) accept_next();
  });
}

void Listener::accept_next() {
  const Strand strand = asio::make_strand(io_);
  acceptor_.async_accept(strand, [this, strand](boost::system::error_code ec, tcp::socket socket) {
    if (ec == asio::error::operation_aborted) return;
    if (ec) return accept_later(ec);  // EMFILE and the like: retrying at once would spin
    if (backoff_.count() != 0) {
      std::cerr << "fnet-server: accepting connections on port " << port() << " again\n";
      backoff_ = std::chrono::milliseconds(0);
    }
    if (*connections_ >= max_connections_) {
      boost::system::error_code ignored;
      socket.non_blocking(true, ignored);
      socket.write_some(asio::buffer(refusal_), ignored);
      socket.close(ignored);
    } else {
      ++*connections_;
      std::shared_ptr<void> slot(nullptr, [count = connections_](void*) { --*count; });
      start_(std::move(socket), strand, std::move(slot));
    }
    accept_next();
  });
}

}  // namespace fnet::rpc
