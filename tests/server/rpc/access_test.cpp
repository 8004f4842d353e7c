// Who may use the API: the token's file and its comparison, and a TCP connection to a server that
// asks for a token — refused with error -32007 and closed before any method runs unless its first
// request is auth with the token.
#include "server/rpc/access.hpp"

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>
#include <gtest/gtest.h>

#include "server/rpc/rpc_server.hpp"
#include "tests/e2e/line_connection.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::rpc {
namespace {

using namespace std::chrono_literals;
const std::string kToken = "0123456789abcdef-TOKEN";

TEST(Access, SameSecretComparesWholeTexts) {
  EXPECT_TRUE(same_secret(kToken, kToken));
  EXPECT_FALSE(same_secret(kToken, kToken + "x"));
  EXPECT_FALSE(same_secret(kToken, kToken.substr(0, kToken.size() - 1)));
  EXPECT_FALSE(same_secret(kToken, ""));
  EXPECT_FALSE(same_secret(kToken, std::string(kToken).replace(0, 1, "1")));
  EXPECT_FALSE(same_secret(kToken, kToken + kToken)) << "a repetition of the secret is not the secret";
  EXPECT_TRUE(Access{}.admits("anything"));
  EXPECT_FALSE(Access{kToken}.admits(""));
}

TEST(Access, ATokenFileHoldsOneLineOfAtLeastSixteenUrlSafeCharacters) {
  testing::TempDir dir;
  EXPECT_EQ(read_token_file(dir.write("ok", kToken + "\n").string()), kToken);
  const auto error_of = [&](const std::string& name, const std::string& text) {
    try {
      read_token_file(dir.write(name, text).string());
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("short", "abc\n").find("fewer than 16"), std::string::npos);
  EXPECT_NE(error_of("space", "0123456789abcdef ghi").find("character 17"), std::string::npos);
  EXPECT_NE(error_of("two", kToken + "\n" + kToken + "\n").find("character 23"), std::string::npos);
  try {
    read_token_file((dir.path() / "missing").string());
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
}

TEST(Access, LoopbackAddresses) {
  EXPECT_TRUE(is_loopback("127.0.0.1"));
  EXPECT_TRUE(is_loopback("127.3.2.1"));
  EXPECT_TRUE(is_loopback("::1"));
  EXPECT_FALSE(is_loopback("0.0.0.0"));
  EXPECT_FALSE(is_loopback("10.0.0.1"));
  EXPECT_FALSE(is_loopback("::"));
  EXPECT_FALSE(is_loopback("localhost")) << "an address, not a name";
}

// A TCP server whose one method, "echo", counts its calls.
class TokenServer {
 public:
  explicit TokenServer(std::string token) {
    server_.emplace(
        io_, "127.0.0.1", 0,
        [this](const std::string&, const json& params, const std::shared_ptr<Peer>&, Completion done) {
          ++calls;
          done(params, nullptr);
        },
        ServerLimits{}, Access{std::move(token)});
    thread_ = std::thread([this] { io_.run(); });
  }
  ~TokenServer() {
    server_->stop();
    io_.stop();
    thread_.join();
  }
  unsigned short port() const { return server_->port(); }
  std::atomic<int> calls{0};

 private:
  boost::asio::io_context io_;
  std::optional<Server> server_;
  std::thread thread_;
};

std::string line(int id, const std::string& method, const json& params = json::object()) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump();
}

TEST(Access, AConnectionWithoutTheTokenIsRefusedAndClosedBeforeAnyMethodRuns) {
  TokenServer s(kToken);
  for (const std::string& first : {line(1, "echo"), std::string("not json"), "[" + line(1, "echo") + "]"}) {
    e2e::LineConnection c(s.port());
    c.send(first);
    c.send(line(2, "echo"));
    const auto refusal = c.next(5s);
    ASSERT_TRUE(refusal) << first;
    EXPECT_EQ((*refusal)["error"]["code"], kUnauthorized) << *refusal;
    EXPECT_NE((*refusal)["error"]["message"].get<std::string>().find("\"method\":\"auth\""), std::string::npos);
    EXPECT_FALSE(c.next(2s)) << "the connection stayed open after " << first;
  }
  e2e::LineConnection wrong(s.port());
  wrong.send(line(1, "auth", {{"token", kToken + "x"}}));
  wrong.send(line(2, "echo"));
  const auto refusal = wrong.next(5s);
  ASSERT_TRUE(refusal);
  EXPECT_EQ((*refusal)["id"], 1);
  EXPECT_EQ((*refusal)["error"]["message"], "unauthorized: wrong token");
  EXPECT_FALSE(wrong.next(2s));
  EXPECT_EQ(s.calls, 0) << "a method ran on a connection without the token";
}

TEST(Access, AConnectionThatPresentsTheTokenIsServed) {
  TokenServer s(kToken);
  e2e::LineConnection c(s.port());
  EXPECT_EQ(c.call("auth", {{"token", kToken}})["result"]["authenticated"], true);
  EXPECT_EQ(c.call("echo", {{"n", 1}})["result"]["n"], 1);
  EXPECT_EQ(s.calls, 1);
  // A server that asks for no token takes the auth request of a client that has one.
  TokenServer open("");
  e2e::LineConnection o(open.port());
  EXPECT_EQ(o.call("auth", {{"token", "whatever"}})["result"]["authenticated"], true);
  EXPECT_EQ(o.call("echo", {{"n", 2}})["result"]["n"], 2);
}

}  // namespace
}  // namespace fnet::rpc
