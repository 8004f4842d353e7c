// The dashboard's transport on real sockets on loopback: the page and its files over HTTP, 4xx for
// what is not served or not HTTP, and the JSON-RPC WebSocket with the API's errors for malformed,
// oversized and binary messages; a tab that stops reading is dropped without delaying the others;
// connections are bounded. The handler here is a test's; websocket_api_test.cpp drives make_api.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it
#include <vector>

#include <gtest/gtest.h>

#include "server/web/http_server.hpp"
#include "server/web/web_assets.hpp"
#include "tests/server/web/web_client.hpp"

namespace fnet::web {
namespace {

using namespace std::chrono_literals;
using namespace fnet::web::testing;
using json = nlohmann::json;

// "echo" ends at once with its params; "fail" throws; "flood" sends `count` notifications of
// `bytes` bytes each to its caller and ends with how many the connection took.
class WebFixture {
 public:
  explicit WebFixture(rpc::ServerLimits limits = {}) {
    server_.emplace(
        io_, "127.0.0.1", 0,
        [this](const std::string& method, const json& params, const std::shared_ptr<rpc::Peer>& peer,
               rpc::Completion done) {
          if (method == "echo") return done(params, nullptr);
          if (method == "fail") throw rpc::Error(rpc::kInvalidParams, "bad");
          if (method == "flood") {
            const std::string filler(params["bytes"].get<std::size_t>(), 'x');
            std::size_t taken = 0;
            for (int k = 0; k < params["count"].get<int>(); ++k)
              if (peer->send(rpc::notification("filler", {{"k", k}, {"text", filler}}))) ++taken;
            flooded_ = true;
            return done(json{{"taken", taken}}, nullptr);
          }
          throw rpc::Error(rpc::kMethodNotFound, "unknown method '" + method + "'");
        },
        limits);
    for (auto& t : threads_) t = std::thread([this] { io_.run(); });
  }
  ~WebFixture() {
    server_->stop();
    io_.stop();
    for (auto& t : threads_) t.join();
  }
  unsigned short port() const { return server_->port(); }
  std::size_t connections() const { return server_->connections(); }
  bool flooded() const { return flooded_; }

 private:
  boost::asio::io_context io_;
  std::optional<HttpServer> server_;
  std::thread threads_[2];
  std::atomic<bool> flooded_{false};
};

std::string request_text(int id, const std::string& method, const json& params = json::object()) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump();
}

TEST(WebServer, ServesThePageAndItsFilesAndRefusesWhatItDoesNotServe) {
  WebFixture f;
  const auto page = http_request(f.port(), http::verb::get, "/");
  EXPECT_EQ(page.result(), http::status::ok);
  EXPECT_EQ(page[http::field::content_type], "text/html; charset=utf-8");
  EXPECT_EQ(page.body(), std::string(find_asset("/index.html")->body));
  EXPECT_NE(page["Content-Security-Policy"].find("default-src 'self'"), std::string::npos);
  const auto same = http_request(f.port(), http::verb::get, "/index.html?x=1");
  EXPECT_EQ(same.body(), page.body());

  const auto missing = http_request(f.port(), http::verb::get, "/../etc/passwd");
  EXPECT_EQ(missing.result(), http::status::not_found);
  EXPECT_EQ(missing.body(), "not found: /../etc/passwd\n");
  EXPECT_EQ(http_request(f.port(), http::verb::post, "/").result(), http::status::method_not_allowed);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/rpc").result(), http::status::upgrade_required);

  EXPECT_EQ(raw_exchange(f.port(), "NOT HTTP AT ALL\r\n\r\n").rfind("HTTP/1.1 400 Bad Request\r\n", 0), 0u);
  const std::string huge = "GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(100000, 'a') + "\r\n\r\n";
  EXPECT_EQ(raw_exchange(f.port(), huge).rfind("HTTP/1.1 413 Payload Too Large\r\n", 0), 0u);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/").result(), http::status::ok) << "the server went down";
}

TEST(WebServer, KeepsAConnectionOpenForTheNextRequest) {
  WebFixture f;
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), f.port()));
  for (const char* target : {"/", "/nope", "/index.html"}) {
    http::request<http::string_body> request{http::verb::get, target, 11};
    request.set(http::field::host, "127.0.0.1");
    http::write(stream, request);
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(stream, buffer, response);
    EXPECT_EQ(response.result(), std::string(target) == "/nope" ? http::status::not_found : http::status::ok);
  }
}

TEST(WebServer, ClosesTheConnectionWhenTheRequestSaysClose) {
  WebFixture f;
  const std::string answer = raw_exchange(f.port(), "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(answer.rfind("HTTP/1.1 200 OK\r\n", 0), 0u) << answer.substr(0, 200);
  EXPECT_NE(answer.find("Connection: close\r\n"), std::string::npos) << "the answer did not say it closes";
}

TEST(WebServer, CarriesJsonRpcOverAWebSocket) {
  WebFixture f;
  WsClient ws(f.port());
  const json echo = ws.call("echo", {{"n", 7}});
  EXPECT_EQ(echo["result"]["n"], 7);
  EXPECT_EQ(ws.call("fail")["error"]["code"], rpc::kInvalidParams);
  EXPECT_EQ(ws.call("nope")["error"]["code"], rpc::kMethodNotFound);
  ws.send("[" + request_text(1, "echo", {{"a", 1}}) + "," + request_text(2, "fail") + "]");
  const auto batch = ws.next();
  ASSERT_TRUE(batch && batch->is_array());
  ASSERT_EQ(batch->size(), 2u);
  EXPECT_EQ((*batch)[0]["result"]["a"], 1);
  const auto flood = ws.call("flood", {{"count", 3}, {"bytes", 10}});
  EXPECT_EQ(flood["result"]["taken"], 3);
}

TEST(WebServer, MalformedAndBinaryMessagesGetTheApisErrorsAndTheConnectionStays) {
  WebFixture f;
  WsClient ws(f.port());
  ws.send("{\"jsonrpc\":\"2.0\",\"id\":1,");
  auto reply = ws.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["error"]["code"], rpc::kParseError);
  ws.send("{\"jsonrpc\":\"1.0\",\"id\":2,\"method\":\"echo\"}");
  reply = ws.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["error"]["code"], rpc::kInvalidRequest);
  ws.send_binary(std::string("\x00\x01\x02", 3));
  reply = ws.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["error"]["code"], rpc::kInvalidRequest);
  EXPECT_NE((*reply)["error"]["message"].get<std::string>().find("binary"), std::string::npos);
  EXPECT_EQ(ws.call("echo", {{"still", true}})["result"]["still"], true);
  // A number past a double and nesting 400 000 deep (in under 1 MiB): errors, and the tab goes on.
  ws.send(R"({"jsonrpc":"2.0","id":3,"method":"echo","params":{"x":1e999}})");
  reply = ws.next();
  ASSERT_TRUE(reply) << "the server died";
  EXPECT_EQ((*reply)["error"]["code"], rpc::kParseError);
  ws.send(R"({"jsonrpc":"2.0","id":4,"method":"echo","params":)" + std::string(400000, '[') + std::string(400000, ']') +
          "}");
  reply = ws.next();
  ASSERT_TRUE(reply) << "the server died";
  EXPECT_EQ((*reply)["error"]["data"]["limit"], "max_json_depth");
  EXPECT_EQ(ws.call("echo", {{"still", 2}})["result"]["still"], 2);
}

TEST(WebServer, AnOversizedMessageGetsAnErrorThenTheConnectionCloses) {
  rpc::ServerLimits limits;
  limits.max_line_bytes = 1000;
  WebFixture f(limits);
  WsClient ws(f.port());
  ws.send(request_text(1, "echo", {{"text", std::string(200000, 'y')}}));
  const auto reply = ws.next();
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["error"]["code"], rpc::kInvalidRequest);
  EXPECT_EQ((*reply)["error"]["message"], "message longer than 1000 bytes; closing the connection");
  EXPECT_FALSE(ws.next(5s));
  EXPECT_EQ(ws.last_error, websocket::error::closed);
  EXPECT_EQ(ws.close_reason().code, websocket::close_code::too_big);
  WsClient other(f.port());
  EXPECT_EQ(other.call("echo", {{"n", 1}})["result"]["n"], 1) << "the server went down";
}

TEST(WebServer, ATabThatStopsReadingIsDroppedAndNeverDelaysTheOthers) {
  rpc::ServerLimits limits;
  limits.max_queued_bytes = 1 << 20;
  limits.write_timeout = rpc::Seconds(1);
  WebFixture f(limits);
  WsClient stalled(f.port());
  WsClient reader(f.port());
  // 64 MiB for a client that reads nothing: far more than the socket buffers and the bound hold.
  stalled.send(request_text(1, "flood", {{"count", 1024}, {"bytes", 64 << 10}}));
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!f.flooded() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
  ASSERT_TRUE(f.flooded());
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(reader.call("echo", {{"n", 2}})["result"]["n"], 2);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 1s) << "the reader waited for the stalled tab";
  // The stalled tab was dropped: what it reads ends before 64 MiB, with the connection closed.
  std::size_t bytes = 0;
  while (const auto m = stalled.next_text(5s)) bytes += m->size();
  EXPECT_LT(bytes, std::size_t{8} << 20);
  EXPECT_TRUE(stalled.last_error) << "the stalled tab's connection stayed open";
}

TEST(WebServer, ConnectionsAreBounded) {
  rpc::ServerLimits limits;
  limits.max_connections = 2;
  WebFixture f(limits);
  {
    WsClient a(f.port());
    WsClient b(f.port());
    EXPECT_EQ(a.call("echo", {{"n", 1}})["result"]["n"], 1);
    EXPECT_EQ(raw_exchange(f.port(), "GET / HTTP/1.1\r\nHost: x\r\n\r\n").rfind("HTTP/1.1 503 ", 0), 0u);
  }
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (f.connections() > 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(f.connections(), 0u) << "closed connections still counted";
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/").result(), http::status::ok);
}

}  // namespace
}  // namespace fnet::web
