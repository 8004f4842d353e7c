#include "server/web/http_connection.hpp"

#include <array>
#include <chrono>
#include <string>
#include <string_view>
#include <type_traits>

#include <boost/beast/websocket.hpp>

#include "server/web/http_access.hpp"
#include "server/web/http_server.hpp"
#include "server/web/web_assets.hpp"
#include "server/web/websocket_peer.hpp"

namespace fnet::web {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

namespace {

constexpr std::size_t kMaxHeaderBytes = 16 << 10;
constexpr std::size_t kMaxBodyBytes = 64 << 10;  // the page only GETs; a body is read to be refused
constexpr auto kRequestTimeout = std::chrono::seconds(30);

// Every response: not cached, not sniffed, not framed, scripts and connections from this server only.
Response response(http::status status, unsigned version, std::string_view type, std::string body) {
  Response r{status, version};
  r.set(http::field::server, "fnet-server");
  r.set(http::field::content_type, beast::string_view(type.data(), type.size()));
  r.set(http::field::cache_control, "no-store");
  r.set("X-Content-Type-Options", "nosniff");
  r.set("Referrer-Policy", "no-referrer");
  r.set("Content-Security-Policy", "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'");
  r.body() = std::move(body);
  r.prepare_payload();
  return r;
}

Response error(http::status status, unsigned version, const std::string& message) {
  return response(status, version, "text/plain; charset=utf-8", message + "\n");
}

// The target without its query.
std::string_view path_of(beast::string_view target) {
  return std::string_view(target.data(), target.size()).substr(0, target.find('?'));
}

}  // namespace

Response answer(const Request& request) {
  const std::string_view path = path_of(request.target());
  if (request.method() != http::verb::get) {
    Response r = error(http::status::method_not_allowed, request.version(), "only GET is served");
    r.set(http::field::allow, "GET");
    return r;
  }
  if (path == kRpcPath)
    return error(http::status::upgrade_required, request.version(),
                 std::string(kRpcPath) + " is the JSON-RPC WebSocket: open it with a WebSocket upgrade");
  const Asset* asset = find_asset(path);
  if (!asset) return error(http::status::not_found, request.version(), "not found: " + std::string(path));
  return response(http::status::ok, request.version(), asset->content_type, std::string(asset->body));
}

template <class Stream>
HttpConnection<Stream>::HttpConnection(Stream stream, rpc::Strand strand, const rpc::ServerLimits& limits,
                                       const rpc::Handler& handler, const rpc::Access& access, unsigned short port,
                                       std::shared_ptr<void> slot)
    : stream_(std::move(stream)),
      strand_(std::move(strand)),
      limits_(limits),
      handler_(handler),
      access_(access),
      port_(port),
      slot_(std::move(slot)) {}

template <class Stream>
void HttpConnection<Stream>::start() {
  asio::dispatch(stream_.get_executor(), [self = this->shared_from_this()] {
    if constexpr (std::is_same_v<Stream, TlsStream>) {
      self->tcp().expires_after(
          std::chrono::duration_cast<std::chrono::steady_clock::duration>(self->limits_.first_request_timeout));
      self->stream_.async_handshake(asio::ssl::stream_base::server, [self](beast::error_code ec) {
        if (ec) return self->tcp().close();
        self->read_request();
      });
    } else {
      self->read_request();
    }
  });
}

template <class Stream>
void HttpConnection<Stream>::read_request() {
  parser_ = std::make_unique<http::request_parser<http::string_body>>();
  parser_->header_limit(kMaxHeaderBytes);
  parser_->body_limit(kMaxBodyBytes);
  tcp().expires_after(kRequestTimeout);  // a client that sends nothing is not held
  http::async_read(stream_, buffer_, *parser_,
                   [self = this->shared_from_this()](beast::error_code ec, std::size_t) { self->on_request(ec); });
}

template <class Stream>
void HttpConnection<Stream>::on_request(beast::error_code ec) {
  if (ec == http::error::end_of_stream || ec == beast::error::timeout || ec == asio::error::operation_aborted)
    return close();
  if (ec == http::error::header_limit || ec == http::error::body_limit) {
    Response r = error(http::status::payload_too_large, 11, "request too large: " + ec.message());
    r.keep_alive(false);
    return send(std::move(r));
  }
  if (ec) {
    if (ec.category() != http::make_error_code(http::error::bad_target).category())
      return close();  // the socket failed
    Response r = error(http::status::bad_request, 11, "malformed HTTP request: " + ec.message());
    r.keep_alive(false);
    return send(std::move(r));
  }
  Request request = parser_->release();
  // The client's "Connection: close" (or HTTP/1.0 without keep-alive) ends the connection after the answer.
  const auto reply = [this, keep = request.keep_alive()](Response r) {
    r.keep_alive(keep && r.keep_alive());
    send(std::move(r));
  };
  const Admission admission = admit(request, access_, port_);
  if (admission.verdict == Admission::Verdict::refuse)
    return reply(error(admission.status, request.version(), admission.message));
  if (admission.verdict == Admission::Verdict::redirect) {
    Response r = error(http::status::see_other, request.version(), "see " + admission.location);
    r.set(http::field::location, admission.location);
    // Over TLS the browser is told never to send the token in clear.
    r.set(http::field::set_cookie,
          admission.set_cookie + (std::is_same_v<Stream, TlsStream> ? std::string("; Secure") : std::string()));
    return reply(std::move(r));
  }
  if (beast::websocket::is_upgrade(request) && path_of(request.target()) == kRpcPath) {
    tcp().expires_never();
    const auto ws = std::make_shared<WebSocketPeer<Stream>>(std::move(stream_), strand_, limits_, handler_, access_,
                                                            [slot = slot_] {});
    ws->accept(std::move(request));
    return;
  }
  reply(answer(request));
}

template <class Stream>
void HttpConnection<Stream>::send(Response response) {
  auto held = std::make_shared<Response>(std::move(response));
  http::async_write(stream_, *held, [self = this->shared_from_this(), held](beast::error_code ec, std::size_t) {
    if (ec || !held->keep_alive()) return self->close();
    self->read_request();
  });
}

// Half-closes (with TLS, its close_notify first), then discards what the client still sends (for
// a few seconds at most), so that closing does not reset the connection and destroy the response
// in flight.
template <class Stream>
void HttpConnection<Stream>::close() {
  tcp().expires_after(std::chrono::seconds(3));
  const auto half_close = [self = this->shared_from_this()] {
    beast::error_code ignored;
    self->tcp().socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
    self->drain();
  };
  if constexpr (std::is_same_v<Stream, TlsStream>)
    stream_.async_shutdown([half_close](beast::error_code) { half_close(); });
  else
    half_close();
}

template <class Stream>
void HttpConnection<Stream>::drain() {
  auto scratch = std::make_shared<std::array<char, 16384>>();
  tcp().async_read_some(asio::buffer(*scratch),
                        [self = this->shared_from_this(), scratch](beast::error_code ec, std::size_t) {
                          if (ec) return self->tcp().close();
                          self->drain();
                        });
}

template class HttpConnection<beast::tcp_stream>;
template class HttpConnection<TlsStream>;

}  // namespace fnet::web
