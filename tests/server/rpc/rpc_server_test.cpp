// The JSON-RPC transport on a real TCP socket on loopback: a call the handler ends later (a heavy
// method on the analysis pool) leaves the connection free for the calls after it, each answer
// matched by its id; a connection with max_pending_calls calls unanswered is not read further
// until one ends; a client that stops sending still gets every answer; a batch is answered whole.
#include "server/rpc/rpc_server.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it
#include <vector>

#include <boost/asio.hpp>
#include <gtest/gtest.h>

#include "tests/e2e/line_connection.hpp"

namespace fnet::rpc {
namespace {

using namespace std::chrono_literals;

// "echo" ends at once with its params; "slow" ends when the test releases it, from another thread;
// "fail" throws; "late_error" ends later with an rpc::Error.
class Fixture {
 public:
  explicit Fixture(ServerLimits limits = {}) {
    server_.emplace(
        io_, "127.0.0.1", 0,
        [this](const std::string& method, const json& params, const std::shared_ptr<Peer>&, Completion done) {
          if (method == "echo") return done(params, nullptr);
          if (method == "fail") throw Error(kInvalidParams, "bad");
          std::lock_guard lock(mutex_);
          held_.push_back({method, params, std::move(done)});
          changed_.notify_all();
        },
        limits);
    thread_ = std::thread([this] { io_.run(); });
  }
  ~Fixture() {
    release_all();
    server_->stop();
    io_.stop();
    thread_.join();
  }
  unsigned short port() const { return server_->port(); }
  // Waits until `n` slow calls are held.
  bool wait_held(std::size_t n, std::chrono::milliseconds timeout = 10s) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return held_.size() >= n; });
  }
  std::size_t held() {
    std::lock_guard lock(mutex_);
    return held_.size();
  }
  // Ends the oldest held call from a thread of its own, as the analysis pool would.
  void release_one() {
    Held h;
    {
      std::lock_guard lock(mutex_);
      h = std::move(held_.front());
      held_.erase(held_.begin());
    }
    std::thread([h = std::move(h)] {
      if (h.method == "late_error")
        h.done(nullptr, std::make_exception_ptr(Error(kNoNetwork, "later")));
      else
        h.done(json{{"slow", h.params}}, nullptr);
    }).join();
  }
  void release_all() {
    while (held() > 0) release_one();
  }

 private:
  struct Held {
    std::string method;
    json params;
    Completion done;
  };
  boost::asio::io_context io_;
  std::optional<Server> server_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Held> held_;
};

std::string request(int id, const std::string& method, const json& params = json::object()) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump();
}

TEST(RpcServer, ACallEndedLaterLeavesTheConnectionFreeAndIsMatchedByItsId) {
  Fixture f;
  e2e::LineConnection c(f.port());
  c.send(request(1, "slow", {{"n", 1}}));
  c.send(request(2, "echo", {{"n", 2}}));
  const auto first = c.next(5s);
  ASSERT_TRUE(first);
  EXPECT_EQ((*first)["id"], 2) << "the quick call waited for the slow one: " << first->dump();
  EXPECT_EQ((*first)["result"]["n"], 2);
  ASSERT_TRUE(f.wait_held(1));
  f.release_one();
  const auto second = c.next(5s);
  ASSERT_TRUE(second);
  EXPECT_EQ((*second)["id"], 1);
  EXPECT_EQ((*second)["result"]["slow"]["n"], 1);
}

TEST(RpcServer, AnErrorEndedLaterIsTheCallersErrorAndAThrowingHandlerEndsItsCall) {
  Fixture f;
  e2e::LineConnection c(f.port());
  c.send(request(7, "late_error"));
  c.send(request(8, "fail"));
  const auto thrown = c.next(5s);
  ASSERT_TRUE(thrown);
  EXPECT_EQ((*thrown)["id"], 8);
  EXPECT_EQ((*thrown)["error"]["code"], kInvalidParams);
  ASSERT_TRUE(f.wait_held(1));
  f.release_one();
  const auto later = c.next(5s);
  ASSERT_TRUE(later);
  EXPECT_EQ((*later)["id"], 7);
  EXPECT_EQ((*later)["error"]["code"], kNoNetwork);
  EXPECT_EQ((*later)["error"]["message"], "later");
}

TEST(RpcServer, AConnectionWithTooManyCallsUnansweredIsReadAgainWhenOneEnds) {
  ServerLimits limits;
  limits.max_pending_calls = 2;
  Fixture f(limits);
  e2e::LineConnection c(f.port());
  c.send(request(1, "slow"));
  c.send(request(2, "slow"));
  c.send(request(3, "echo"));
  ASSERT_TRUE(f.wait_held(2));
  EXPECT_FALSE(c.next(300ms)) << "the third call was read while two were unanswered";
  f.release_one();
  std::vector<int> ids;
  for (int k = 0; k < 2; ++k) {
    const auto m = c.next(5s);
    ASSERT_TRUE(m);
    ids.push_back((*m)["id"].get<int>());
  }
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<int>{1, 3}));
  f.release_all();
  const auto last = c.next(5s);
  ASSERT_TRUE(last);
  EXPECT_EQ((*last)["id"], 2);
}

TEST(RpcServer, AClientThatStopsSendingStillGetsEveryAnswerThenTheConnectionCloses) {
  Fixture f;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket s(io);
  s.connect({boost::asio::ip::make_address("127.0.0.1"), f.port()});
  const std::string text = request(1, "slow") + "\n" + request(2, "echo") + "\n";
  boost::asio::write(s, boost::asio::buffer(text));
  s.shutdown(boost::asio::ip::tcp::socket::shutdown_send);
  ASSERT_TRUE(f.wait_held(1));
  std::this_thread::sleep_for(100ms);  // the end of input is seen while the slow call is held
  f.release_one();
  std::string out;
  char buf[4096];
  boost::system::error_code ec;
  while (std::size_t n = s.read_some(boost::asio::buffer(buf), ec)) out.append(buf, n);
  EXPECT_EQ(ec, boost::asio::error::eof);
  EXPECT_NE(out.find("\"id\":1"), std::string::npos) << out;
  EXPECT_NE(out.find("\"id\":2"), std::string::npos) << out;
}

TEST(RpcServer, ABatchIsAnsweredWholeInRequestOrderOnceItsLastCallEnds) {
  Fixture f;
  e2e::LineConnection c(f.port());
  c.send("[" + request(1, "slow") + "," + request(2, "echo", {{"n", 2}}) + "," + request(3, "fail") + "]");
  ASSERT_TRUE(f.wait_held(1));
  EXPECT_FALSE(c.next(200ms)) << "a batch was answered before its last call ended";
  f.release_one();
  const auto batch = c.next(5s);
  ASSERT_TRUE(batch);
  ASSERT_TRUE(batch->is_array()) << batch->dump();
  ASSERT_EQ(batch->size(), 3u);
  EXPECT_EQ((*batch)[0]["id"], 1);
  EXPECT_EQ((*batch)[1]["result"]["n"], 2);
  EXPECT_EQ((*batch)[2]["error"]["code"], kInvalidParams);
}

}  // namespace
}  // namespace fnet::rpc
