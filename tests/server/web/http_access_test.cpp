// Who may open the dashboard, on real sockets: with a token, the page opened once with ?token=
// sets it as a cookie that the page's requests and its WebSocket carry, and a request without it
// gets 401; without a token, only requests to a loopback host name are answered; a WebSocket
// opens from the server's own pages only.
#include "server/web/http_access.hpp"

#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it

#include <gtest/gtest.h>

#include "server/web/http_server.hpp"
#include "tests/server/web/web_client.hpp"

namespace fnet::web {
namespace {

using namespace fnet::web::testing;
using json = nlohmann::json;
const std::string kSecret = "dashboard-token-0123456789";

class AccessFixture {
 public:
  explicit AccessFixture(std::string token) {
    server_.emplace(
        io_, "127.0.0.1", 0,
        [](const std::string&, const json& params, const std::shared_ptr<rpc::Peer>&, rpc::Completion done) {
          done(params, nullptr);
        },
        rpc::ServerLimits{}, rpc::Access{std::move(token)});
    thread_ = std::thread([this] { io_.run(); });
  }
  ~AccessFixture() {
    server_->stop();
    io_.stop();
    thread_.join();
  }
  unsigned short port() const { return server_->port(); }
  std::string cookie(const std::string& token) const { return token_cookie_name(port()) + "=" + token; }

 private:
  boost::asio::io_context io_;
  std::optional<HttpServer> server_;
  std::thread thread_;
};

TEST(HttpAccess, ThePageTakesTheTokenOnceInTheAddressThenFromItsCookie) {
  AccessFixture f(kSecret);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/").result(), http::status::unauthorized);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/?token=wrong").result(), http::status::unauthorized);
  const auto opened = http_request(f.port(), http::verb::get, "/index.html?token=" + kSecret);
  EXPECT_EQ(opened.result(), http::status::see_other);
  EXPECT_EQ(opened[http::field::location], "/index.html") << "the token stays in the address bar";
  EXPECT_EQ(opened[http::field::set_cookie], f.cookie(kSecret) + "; Path=/; HttpOnly; SameSite=Strict");
  EXPECT_EQ(opened.body().find(kSecret), std::string::npos);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/", Headers().with_cookie("a=b; " + f.cookie(kSecret))).result(),
            http::status::ok);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/", Headers().with_cookie(f.cookie("wrong"))).result(),
            http::status::unauthorized);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/", Headers().with_cookie(token_cookie_name(1) + "=" + kSecret))
                .result(),
            http::status::unauthorized)
      << "another server's cookie";
  // Asked for a token, the server answers any host name: the token is what admits.
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/",
                         Headers().with_cookie(f.cookie(kSecret)).with_host("fnet.example:80"))
                .result(),
            http::status::ok);
}

TEST(HttpAccess, TheWebSocketOpensWithTheTokenOnly) {
  AccessFixture f(kSecret);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/rpc", Headers().as_upgrade()).result(),
            http::status::unauthorized);
  EXPECT_EQ(
      http_request(f.port(), http::verb::get, "/rpc", Headers().with_cookie(f.cookie("nope")).as_upgrade()).result(),
      http::status::unauthorized);
  WsClient with_cookie(f.port(), "/rpc", f.cookie(kSecret));
  EXPECT_EQ(with_cookie.call("echo", {{"n", 1}})["result"]["n"], 1);
  WsClient with_query(f.port(), "/rpc?token=" + kSecret);
  EXPECT_EQ(with_query.call("echo", {{"n", 2}})["result"]["n"], 2);
}

TEST(HttpAccess, AWebSocketOpensFromTheServersOwnPagesOnly) {
  AccessFixture f("");
  const std::string host = "127.0.0.1:" + std::to_string(f.port());
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/rpc", Headers().with_origin("http://evil.example").as_upgrade())
                .result(),
            http::status::forbidden);
  WsClient own(f.port(), "/rpc", "", "http://" + host);
  EXPECT_EQ(own.call("echo", {{"n", 3}})["result"]["n"], 3);
}

TEST(HttpAccess, WithoutATokenOnlyLoopbackHostNamesAreAnswered) {
  AccessFixture f("");
  const std::string port = std::to_string(f.port());
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/").result(), http::status::ok);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/", Headers().with_host("localhost:" + port)).result(),
            http::status::ok);
  EXPECT_EQ(http_request(f.port(), http::verb::get, "/", Headers().with_host("[::1]:" + port)).result(),
            http::status::ok);
  const auto rebound = http_request(f.port(), http::verb::get, "/", Headers().with_host("evil.example:" + port));
  EXPECT_EQ(rebound.result(), http::status::forbidden);
  EXPECT_NE(rebound.body().find("http://127.0.0.1:" + port + "/"), std::string::npos) << rebound.body();
}

}  // namespace
}  // namespace fnet::web
