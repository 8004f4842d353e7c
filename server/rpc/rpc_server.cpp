#include "server/rpc/rpc_server.hpp"

#include <array>
#include <istream>
#include <string>
#include <string_view>
#include <utility>

namespace fnet::rpc {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

TcpPeer::TcpPeer(tcp::socket socket, Strand strand, const ServerLimits& limits, const Handler& handler,
                 const Access& access, std::function<void()> on_end)
    : Connection(std::move(strand), "\n", limits, handler, access, false, std::move(on_end)),
      socket_(std::move(socket)),
      input_(limits.max_line_bytes + 1) {}

namespace {

// "POST / HTTP/1.1": a browser or an HTTP client, which this port does not speak. A page on any
// origin may make the browser send one (a form or a fetch), so it is answered in HTTP and closed
// before any line of it could run as a call.
bool http_request_line(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::size_t method_end = line.find(' ');
  if (method_end < 3 || method_end > 10 || method_end == std::string_view::npos) return false;
  for (std::size_t k = 0; k < method_end; ++k)
    if (line[k] < 'A' || line[k] > 'Z') return false;
  const std::size_t version = line.rfind(' ');
  return version > method_end + 1 && line.substr(version + 1).rfind("HTTP/", 0) == 0;
}

std::string http_refusal() {
  const std::string body =
      "This port speaks newline-delimited JSON-RPC 2.0, not HTTP (proto/api.md); the dashboard is on "
      "fnet-server's --http-port.\n";
  return "HTTP/1.1 400 Bad Request\r\nContent-Type: text/plain; charset=utf-8\r\nConnection: close\r\n"
         "Content-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace

void TcpPeer::read_next() {
  asio::async_read_until(socket_, input_, '\n',
                         asio::bind_executor(strand_, [self = self()](boost::system::error_code ec, std::size_t n) {
                           if (ec == asio::error::not_found)  // the line outgrew the buffer's limit
                             return self->refuse(error_response(nullptr, kInvalidRequest,
                                                                "request line longer than " +
                                                                    std::to_string(self->limits_.max_line_bytes) +
                                                                    " bytes; closing the connection"));
                           if (ec == asio::error::eof) return self->input_ended();
                           if (ec) return self->close();
                           std::string line(n, '\0');
                           std::istream(&self->input_).read(line.data(), static_cast<std::streamsize>(n));
                           line.pop_back();  // '\n'
                           if (std::exchange(self->first_line_, false) && http_request_line(line))
                             return self->refuse_text(http_refusal());
                           self->take_message(line);
                         }));
}

void TcpPeer::write(const std::string& text) {
  asio::async_write(
      socket_, asio::buffer(text),
      asio::bind_executor(strand_, [self = self()](boost::system::error_code ec, std::size_t) { self->written(ec); }));
}

// After the last reply: half-close, then discard what the client is still sending (for at most
// a few seconds) so that closing does not reset the connection and destroy the reply in flight.
void TcpPeer::finish() {
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_send, ignored);
  auto timer = std::make_shared<asio::steady_timer>(socket_.get_executor(), std::chrono::seconds(3));
  timer->async_wait(asio::bind_executor(strand_, [self = self(), timer](boost::system::error_code) { self->close(); }));
  drain(timer);
}

void TcpPeer::drain(const std::shared_ptr<asio::steady_timer>& timer) {
  auto buffer = std::make_shared<std::array<char, 65536>>();
  socket_.async_read_some(
      asio::buffer(*buffer),
      asio::bind_executor(strand_, [self = self(), buffer, timer](boost::system::error_code ec, std::size_t) {
        if (ec) {
          timer->cancel();
          return self->close();
        }
        self->drain(timer);
      }));
}

void TcpPeer::close_transport() {
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

namespace {

std::string busy_line(std::size_t max_connections) {
  return error_response(nullptr, kServerBusy, "too many connections (" + std::to_string(max_connections) + ")").dump() +
         "\n";
}

}  // namespace

Server::Server(asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
               ServerLimits limits, Access access)
    : handler_(std::move(handler)),
      limits_(limits),
      access_(std::move(access)),
      listener_(io, address, port, limits_.max_connections, busy_line(limits_.max_connections),
                [this](tcp::socket socket, Strand strand, std::shared_ptr<void> slot) {
                  std::make_shared<TcpPeer>(std::move(socket), std::move(strand), limits_, handler_, access_,
                                            [slot = std::move(slot)] {})
                      ->start();
                }) {}

}  // namespace fnet::rpc
