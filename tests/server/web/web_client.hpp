// The dashboard's clients in the tests, on real sockets with Boost.Beast: one HTTP request and its
// response, and a JSON-RPC WebSocket whose reads end after a timeout.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace fnet::web::testing {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

// Headers a request carries beyond Host (which `host` replaces when given).
struct Headers {
  std::string cookie, origin, host;
  bool upgrade = false;  // a WebSocket upgrade
  Headers& with_cookie(std::string v) { return cookie = std::move(v), *this; }
  Headers& with_origin(std::string v) { return origin = std::move(v), *this; }
  Headers& with_host(std::string v) { return host = std::move(v), *this; }
  Headers& as_upgrade() { return upgrade = true, *this; }
};

// One request on a connection of its own; the response as the server wrote it.
inline http::response<http::string_body> http_request(unsigned short port, http::verb verb, const std::string& target,
                                                      const Headers& headers = {},
                                                      const std::string& address = "127.0.0.1") {
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(boost::asio::ip::make_address(address), port));
  http::request<http::string_body> request{verb, target, 11};
  request.set(http::field::host, headers.host.empty() ? address + ":" + std::to_string(port) : headers.host);
  if (!headers.cookie.empty()) request.set(http::field::cookie, headers.cookie);
  if (!headers.origin.empty()) request.set(http::field::origin, headers.origin);
  if (headers.upgrade) {
    request.set(http::field::upgrade, "websocket");
    request.set(http::field::connection, "Upgrade");
    request.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
    request.set(http::field::sec_websocket_version, "13");
  }
  request.prepare_payload();
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(stream, buffer, response);
  return response;
}

// Bytes written as they are (a malformed request), and what the server answered until it closed.
inline std::string raw_exchange(unsigned short port, const std::string& bytes) {
  boost::asio::io_context io;
  tcp::socket socket(io);
  socket.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  boost::system::error_code ec;
  boost::asio::write(socket, boost::asio::buffer(bytes), ec);  // the server may answer before it read all
  std::string out;
  char chunk[4096];
  while (std::size_t n = socket.read_some(boost::asio::buffer(chunk), ec)) out.append(chunk, n);
  return out;
}

class WsClient {
 public:
  // Opens kRpcPath; `cookie` and `origin` are sent with the upgrade when given.
  explicit WsClient(unsigned short port, const std::string& target = "/rpc", const std::string& cookie = "",
                    const std::string& origin = "", const std::string& address = "127.0.0.1")
      : ws_(io_) {
    beast::get_lowest_layer(ws_).connect(tcp::endpoint(boost::asio::ip::make_address(address), port));
    ws_.set_option(websocket::stream_base::decorator([&](websocket::request_type& r) {
      if (!cookie.empty()) r.set(http::field::cookie, cookie);
      if (!origin.empty()) r.set(http::field::origin, origin);
    }));
    ws_.handshake(address + ":" + std::to_string(port), target);
  }
  void send(const std::string& text) {
    ws_.text(true);
    ws_.write(boost::asio::buffer(text));
  }
  void send_binary(const std::string& bytes) {
    ws_.binary(true);
    ws_.write(boost::asio::buffer(bytes));
  }
  // The next message as text; nullopt on timeout (the stream is then unusable) or when closed.
  std::optional<std::string> next_text(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    beast::flat_buffer buffer;
    bool done = false;
    beast::error_code result;
    ws_.async_read(buffer, [&](beast::error_code ec, std::size_t) {
      done = true;
      result = ec;
    });
    io_.restart();
    io_.run_for(timeout);
    if (!done) {
      beast::get_lowest_layer(ws_).close();
      io_.restart();
      io_.run();
      return std::nullopt;
    }
    last_error = result;
    if (result) return std::nullopt;
    return beast::buffers_to_string(buffer.data());
  }
  std::optional<nlohmann::json> next(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    const auto text = next_text(timeout);
    if (!text) return std::nullopt;
    return nlohmann::json::parse(*text);
  }
  // The response to request `id`, notifications before it skipped.
  nlohmann::json call(const std::string& method, const nlohmann::json& params = nlohmann::json::object()) {
    const int id = next_id_++;
    send(nlohmann::json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump());
    while (const auto m = next())
      if (m->contains("id") && (*m)["id"] == id) return *m;
    return nullptr;
  }
  websocket::close_reason close_reason() const { return ws_.reason(); }
  beast::error_code last_error;

 private:
  boost::asio::io_context io_;
  websocket::stream<beast::tcp_stream> ws_;
  int next_id_ = 1;
};

}  // namespace fnet::web::testing
