#include "server/web/websocket_peer.hpp"

#include <string>

namespace fnet::web {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;

namespace {
constexpr std::size_t kReadChunk = 64 << 10;
}

template <class Stream>
WebSocketPeer<Stream>::WebSocketPeer(Stream stream, rpc::Strand strand, const rpc::ServerLimits& limits,
                                     const rpc::Handler& handler, const rpc::Access& access,
                                     std::function<void()> on_end)
    : Connection(std::move(strand), "", limits, handler, access, true, std::move(on_end)), ws_(std::move(stream)) {
  // The bound on a message is ours (read_next), so that its client is told why it is closed.
  ws_.read_message_max(0);
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.text(true);
}

template <class Stream>
void WebSocketPeer<Stream>::accept(beast::http::request<beast::http::string_body> upgrade) {
  auto request = std::make_shared<beast::http::request<beast::http::string_body>>(std::move(upgrade));
  asio::post(strand_, [self = this->self(), request] {
    self->ws_.async_accept(*request, asio::bind_executor(self->strand_, [self, request](beast::error_code ec) {
      if (ec) return self->close();
      self->start();
    }));
  });
}

// A message is read in chunks, so that one longer than the limit is refused once the limit is
// passed, before the rest of it is held.
template <class Stream>
void WebSocketPeer<Stream>::read_next() {
  ws_.async_read_some(
      input_, kReadChunk, asio::bind_executor(strand_, [self = this->self()](beast::error_code ec, std::size_t) {
        if (ec == websocket::error::closed) return self->input_ended();
        if (ec) return self->close();
        if (self->input_.size() > self->limits_.max_line_bytes) {
          self->input_.clear();
          self->close_code_ = websocket::close_code::too_big;
          return self->refuse(rpc::error_response(nullptr, rpc::kInvalidRequest,
                                                  "message longer than " +
                                                      std::to_string(self->limits_.max_line_bytes) +
                                                      " bytes; closing the connection"));
        }
        if (!self->ws_.is_message_done()) return self->read_next();
        if (self->ws_.got_binary()) {
          self->input_.clear();
          self->send(rpc::error_response(nullptr, rpc::kInvalidRequest,
                                         "a binary message: requests are JSON text, one per WebSocket text message"));
          return self->take_message({});
        }
        const std::string text = beast::buffers_to_string(self->input_.data());
        self->input_.clear();
        self->take_message(text);
      }));
}

template <class Stream>
void WebSocketPeer<Stream>::write(const std::string& text) {
  ws_.async_write(
      asio::buffer(text),
      asio::bind_executor(strand_, [self = this->self()](beast::error_code ec, std::size_t) { self->written(ec); }));
}

template <class Stream>
bool WebSocketPeer<Stream>::is_open() const {
  return beast::get_lowest_layer(ws_).socket().is_open();
}

// The closing handshake (bounded by the stream's handshake timeout), then the socket.
template <class Stream>
void WebSocketPeer<Stream>::finish() {
  ws_.async_close(close_code_,
                  asio::bind_executor(strand_, [self = this->self()](beast::error_code) { self->close(); }));
}

template <class Stream>
void WebSocketPeer<Stream>::close_transport() {
  beast::error_code ignored;
  auto& socket = beast::get_lowest_layer(ws_).socket();
  socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket.close(ignored);
}

template class WebSocketPeer<beast::tcp_stream>;
template class WebSocketPeer<beast::ssl_stream<beast::tcp_stream>>;

}  // namespace fnet::web
