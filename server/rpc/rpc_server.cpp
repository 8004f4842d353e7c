#include "server/rpc/rpc_server.hpp"

#include <array>
#include <istream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace fnet::rpc {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

template <class Stream>
LinePeer<Stream>::LinePeer(Stream stream, Strand strand, const ServerLimits& limits, const Handler& handler,
                           const Access& access, std::function<void()> on_end)
    : Connection(std::move(strand), "\n", limits, handler, access, false, std::move(on_end)),
      stream_(std::move(stream)),
      input_(limits.max_line_bytes + 1) {}

template <class Stream>
void LinePeer<Stream>::handshake_then_start() {
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    auto deadline = std::make_shared<asio::steady_timer>(
        socket().get_executor(),
        std::chrono::duration_cast<asio::steady_timer::duration>(limits_.first_request_timeout));
    asio::post(strand_, [self = self(), deadline] {
      deadline->async_wait(asio::bind_executor(self->strand_, [self](boost::system::error_code ec) {
        if (!ec) self->close_transport();  // the handshake then fails, and the peer ends
      }));
      self->stream_.async_handshake(asio::ssl::stream_base::server,
                                    asio::bind_executor(self->strand_, [self, deadline](boost::system::error_code ec) {
                                      deadline->cancel();
                                      if (ec) return self->close_transport();
                                      self->start();
                                    }));
    });
  } else {
    start();
  }
}

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

template <class Stream>
void LinePeer<Stream>::read_next() {
  asio::async_read_until(stream_, input_, '\n',
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

template <class Stream>
void LinePeer<Stream>::write(const std::string& text) {
  asio::async_write(
      stream_, asio::buffer(text),
      asio::bind_executor(strand_, [self = self()](boost::system::error_code ec, std::size_t) { self->written(ec); }));
}

// After the last reply: half-close (with TLS, its close_notify first), then discard what the
// client is still sending (for at most a few seconds) so that closing does not reset the
// connection and destroy the reply in flight.
template <class Stream>
void LinePeer<Stream>::finish() {
  auto timer = std::make_shared<asio::steady_timer>(socket().get_executor(), std::chrono::seconds(3));
  timer->async_wait(asio::bind_executor(strand_, [self = self(), timer](boost::system::error_code) { self->close(); }));
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    stream_.async_shutdown(asio::bind_executor(strand_, [self = self(), timer](boost::system::error_code) {
      boost::system::error_code ignored;
      self->socket().shutdown(tcp::socket::shutdown_send, ignored);
      self->drain(timer);
    }));
  } else {
    boost::system::error_code ignored;
    socket().shutdown(tcp::socket::shutdown_send, ignored);
    drain(timer);
  }
}

template <class Stream>
void LinePeer<Stream>::drain(const std::shared_ptr<asio::steady_timer>& timer) {
  auto buffer = std::make_shared<std::array<char, 65536>>();
  socket().async_read_some(
      asio::buffer(*buffer),
      asio::bind_executor(strand_, [self = self(), buffer, timer](boost::system::error_code ec, std::size_t) {
        if (ec) {
          timer->cancel();
          return self->close();
        }
        self->drain(timer);
      }));
}

template <class Stream>
void LinePeer<Stream>::close_transport() {
  boost::system::error_code ignored;
  socket().shutdown(tcp::socket::shutdown_both, ignored);
  socket().close(ignored);
}

template class LinePeer<tcp::socket>;
template class LinePeer<TlsStream>;

namespace {

std::string busy_line(std::size_t max_connections) {
  return error_response(nullptr, kServerBusy, "too many connections (" + std::to_string(max_connections) + ")").dump() +
         "\n";
}

}  // namespace

Server::Server(asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
               ServerLimits limits, Access access, TlsContext tls)
    : handler_(std::move(handler)),
      limits_(limits),
      access_(std::move(access)),
      tls_(std::move(tls)),
      // A TLS client could not read a plain line: beyond the bound it is only closed.
      listener_(io, address, port, limits_.max_connections, tls_ ? "" : busy_line(limits_.max_connections),
                [this](tcp::socket socket, Strand strand, std::shared_ptr<void> slot) {
                  if (tls_)
                    std::make_shared<TlsPeer>(TlsStream(std::move(socket), *tls_), std::move(strand), limits_, handler_,
                                              access_, [slot = std::move(slot)] {})
                        ->handshake_then_start();
                  else
                    std::make_shared<TcpPeer>(std::move(socket), std::move(strand), limits_, handler_, access_,
                                              [slot = std::move(slot)] {})
                        ->start();
                }) {}

}  // namespace fnet::rpc
