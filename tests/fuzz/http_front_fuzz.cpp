// fnet-server's HTTP front as a browser and the dashboard reach it: the bytes one client sends on
// one connection, read by the server's own HttpConnection (Boost.Beast's parser within the
// server's bounds, who may open the page, the answer or the WebSocket upgrade at /rpc) and, past
// an upgrade, its WebSocketPeer (frames into the connection's JSON-RPC path, make_api over a
// stored run). An input that holds the word "token" (a query parameter, a cookie, the auth call)
// is served by a server that asks kToken, any other by one that asks none (loopback Host names
// only), so that each input is served once and both admissions are reached. The
// connection is one end of a socket pair; the client's end sends the input, then ends its
// output, and reads until the server closes. Whatever the bytes: no crash, no sanitizer report,
// and the server closes the connection (an input it holds open is a hang).
// Input: the bytes the client sends.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string_view>
#include <sys/socket.h>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>

#include "server/rpc/access.hpp"
#include "server/rpc/server_limits.hpp"
#include "server/web/http_connection.hpp"
#include "tests/fuzz/api_over_store.hpp"

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;

// The port the server is told it listens on: it names the token's cookie, fnet_token_8080.
constexpr unsigned short kPort = 8080;
constexpr const char* kToken = "fuzz-token-0123456789";

// Reads what the server sends until it closes the connection.
class Sink {
 public:
  explicit Sink(asio::local::stream_protocol::socket& socket) : socket_(socket) {}
  void read() {
    socket_.async_read_some(asio::buffer(bytes_), [this](const boost::system::error_code& ec, std::size_t) {
      if (!ec) read();
    });
  }

 private:
  asio::local::stream_protocol::socket& socket_;
  std::array<char, 64 << 10> bytes_;
};

void serve(asio::io_context& io, const fnet::rpc::Handler& handler, const fnet::rpc::Access& access,
           const std::uint8_t* data, std::size_t size) {
  static const fnet::rpc::ServerLimits limits;
  int ends[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) {
    std::cerr << "fuzz: socketpair failed\n";
    std::abort();
  }
  asio::ip::tcp::socket server_end(io);
  server_end.assign(asio::ip::tcp::v4(), ends[0]);
  asio::local::stream_protocol::socket client(io);
  client.assign(asio::local::stream_protocol(), ends[1]);
  std::make_shared<fnet::web::HttpConnection<beast::tcp_stream>>(
      beast::tcp_stream(std::move(server_end)), asio::make_strand(io), limits, handler, access, kPort, nullptr)
      ->start();
  asio::async_write(client, asio::buffer(data, size), [&client](const boost::system::error_code&, std::size_t) {
    boost::system::error_code ignored;
    client.shutdown(asio::socket_base::shutdown_send, ignored);
  });
  Sink sink(client);
  sink.read();
  io.restart();
  io.run();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fnet::fuzz::ApiOverStore api;
  static asio::io_context io;
  static const fnet::rpc::Access open_access{};
  static const fnet::rpc::Access token_access{kToken};
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  serve(io, api.handler, text.find("token") != std::string_view::npos ? token_access : open_access, data, size);
  return 0;
}
