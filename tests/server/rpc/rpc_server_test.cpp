// The JSON-RPC transport on a real TCP socket on loopback: a call the handler ends later (a heavy
// method on the analysis pool) leaves the connection free for the calls after it, each answer
// matched by its id; a connection with max_calls_in_progress calls unanswered is not read
// further until one ends; a client that stops sending still gets every answer; a batch is answered whole.
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
#include "tests/server/rpc/held_calls_server.hpp"

namespace fnet::rpc {
namespace {

using namespace std::chrono_literals;

TEST(RpcServer, ACallEndedLaterLeavesTheConnectionFreeAndIsMatchedByItsId) {
  HeldCallsServer f;
  e2e::LineConnection c(f.port());
  c.send(request_line(1, "slow", {{"n", 1}}));
  c.send(request_line(2, "echo", {{"n", 2}}));
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
  HeldCallsServer f;
  e2e::LineConnection c(f.port());
  c.send(request_line(7, "late_error"));
  c.send(request_line(8, "fail"));
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
  limits.max_calls_in_progress = 2;
  HeldCallsServer f(limits);
  e2e::LineConnection c(f.port());
  c.send(request_line(1, "slow"));
  c.send(request_line(2, "slow"));
  c.send(request_line(3, "echo"));
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
  HeldCallsServer f;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket s(io);
  s.connect({boost::asio::ip::make_address("127.0.0.1"), f.port()});
  const std::string text = request_line(1, "slow") + "\n" + request_line(2, "echo") + "\n";
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
  HeldCallsServer f;
  e2e::LineConnection c(f.port());
  c.send("[" + request_line(1, "slow") + "," + request_line(2, "echo", {{"n", 2}}) + "," + request_line(3, "fail") +
         "]");
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
