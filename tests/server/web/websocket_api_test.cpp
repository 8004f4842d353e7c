// The API's own methods (make_api over a registry) through the dashboard's WebSocket: the same
// answers and errors as on the TCP API, and a subscription made on the WebSocket ended with it.
#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>

#include "server/api/api_methods.hpp"
#include "server/web/http_server.hpp"
#include "tests/server/web/web_client.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::web {
namespace {

using namespace std::chrono_literals;
using json = nlohmann::json;

struct ApiOverWebSocket {
  fnet::testing::TempDir dir;
  boost::asio::thread_pool pool{1};
  server::Registry registry{dir.path(), pool};
  server::ApiContext context{registry};
  boost::asio::io_context io;
  std::optional<HttpServer> http;
  std::thread thread;
  ApiOverWebSocket() {
    http.emplace(io, "127.0.0.1", 0, server::make_api(context));
    thread = std::thread([this] { io.run(); });
  }
  ~ApiOverWebSocket() {
    http->stop();
    io.stop();
    thread.join();
  }
};

TEST(WebSocketApi, AnswersTheApisMethodsWithTheApisErrors) {
  ApiOverWebSocket s;
  testing::WsClient ws(s.http->port());
  EXPECT_EQ(ws.call("runs.list")["result"], json({{"runs", json::array()}}));
  const json unknown_run = ws.call("run.get", {{"run", "nope"}});
  EXPECT_EQ(unknown_run["error"]["code"], rpc::kUnknownRun);
  EXPECT_EQ(unknown_run["error"]["data"]["run"], "nope");
  const json network = ws.call("network.get", {{"run", "nope"}, {"frame", 0}});
  EXPECT_EQ(network["error"]["code"], rpc::kUnknownRun) << network;
  EXPECT_EQ(ws.call("series.get", {{"metric", "bottleneck"}, {"dimension", 1}})["error"]["data"]["parameter"],
            "dimension");
  EXPECT_EQ(ws.call("no.such.method")["error"]["code"], rpc::kMethodNotFound);
}

TEST(WebSocketApi, ASubscriptionEndsWithItsWebSocket) {
  ApiOverWebSocket s;
  {
    testing::WsClient ws(s.http->port());
    const json subscribed = ws.call("series.subscribe");
    ASSERT_TRUE(subscribed.contains("result")) << subscribed;
    EXPECT_EQ(subscribed["result"]["run"], nullptr);
    EXPECT_EQ(s.registry.subscriptions(), 1u);
  }
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (s.registry.subscriptions() > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(10ms);
  EXPECT_EQ(s.registry.subscriptions(), 0u) << "the closed WebSocket's subscription was kept";
}

}  // namespace
}  // namespace fnet::web
