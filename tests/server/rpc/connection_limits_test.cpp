// What a hostile or careless client can make a connection hold, on a real loopback socket: no
// message kills the server or stalls it (numbers past a double, nesting 400 000 deep, an HTTP
// request on the API's port), bounds count the unit that costs (a batch as its calls, answers in
// bytes), every limit passed is said with error -32008 naming it, and deadlines free the slots
// of clients that send nothing.
#include <poll.h>

#include <chrono>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>
#include <gtest/gtest.h>

#include "tests/e2e/line_connection.hpp"
#include "tests/server/rpc/held_calls_server.hpp"

namespace fnet::rpc {
namespace {

using namespace std::chrono_literals;
using tcp = boost::asio::ip::tcp;

// What the server sends until it closes the connection (or `timeout` passes: then `closed` false).
struct Received {
  std::string text;
  bool closed = false;
  std::chrono::milliseconds after{0};  // when it closed, from the call
};

Received read_until_closed(tcp::socket& s, std::chrono::milliseconds timeout) {
  Received r;
  const auto start = std::chrono::steady_clock::now();
  while (true) {
    const auto left =
        timeout - std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
    if (left.count() <= 0) return r;
    pollfd p{s.native_handle(), POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char chunk[65536];
    boost::system::error_code ec;
    const std::size_t n = s.read_some(boost::asio::buffer(chunk), ec);
    r.text.append(chunk, n);
    if (ec) {
      r.closed = true;
      r.after = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
      return r;
    }
  }
}

class RawConnection {
 public:
  explicit RawConnection(unsigned short port) : socket(io_) {
    socket.connect({boost::asio::ip::make_address("127.0.0.1"), port});
  }
  void write(const std::string& text) { boost::asio::write(socket, boost::asio::buffer(text)); }

 private:
  boost::asio::io_context io_;

 public:
  tcp::socket socket;
};

json limit_of(const json& message) { return message["error"]["data"]["limit"]; }

TEST(ConnectionLimits, NumbersPastADoubleAndDeepNestingGetErrorsAndTheConnectionGoesOn) {
  HeldCallsServer f;
  e2e::LineConnection c(f.port());
  c.send("1e999");
  auto m = c.next(5s);
  ASSERT_TRUE(m) << "no answer: the server died";
  EXPECT_EQ((*m)["error"]["code"], kParseError);
  EXPECT_NE((*m)["error"]["message"].get<std::string>().find("1e999"), std::string::npos) << m->dump();
  c.send(R"({"jsonrpc":"2.0","id":1,"method":"echo","params":{"x":-1e400}})");
  m = c.next(5s);
  ASSERT_TRUE(m);
  EXPECT_EQ((*m)["error"]["code"], kParseError);
  // 400 000 levels in under 1 MiB, in the params and in the id: the depth bound answers.
  const std::size_t deep = 400000;
  c.send(R"({"jsonrpc":"2.0","id":2,"method":"echo","params":)" + std::string(deep, '[') + std::string(deep, ']') +
         "}");
  m = c.next(10s);
  ASSERT_TRUE(m) << "no answer: the server died";
  EXPECT_EQ((*m)["error"]["code"], kLimitExceeded);
  EXPECT_EQ(limit_of(*m), "max_json_depth");
  EXPECT_EQ((*m)["error"]["data"]["value"], 64);
  c.send(R"({"jsonrpc":"2.0","method":"echo","id":)" + std::string(deep, '[') + std::string(deep, ']') + "}");
  m = c.next(10s);
  ASSERT_TRUE(m);
  EXPECT_EQ(limit_of(*m), "max_json_depth");
  // 64 levels in all (the request, its params and 62 arrays) are a request like any other.
  c.send(request_line(3, "echo", {{"x", json::parse(std::string(62, '[') + std::string(62, ']'))}}));
  m = c.next(5s);
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->contains("result")) << m->dump().substr(0, 300);
  EXPECT_EQ(f.calls.load(), 1) << "only the well-formed call reached a method";
}

TEST(ConnectionLimits, BeforeTheTokenAnUnreadableLineIsRefusedAndTheServerServesTheNext) {
  HeldCallsServer f({}, Access{"0123456789abcdef-token"});
  {
    RawConnection raw(f.port());
    raw.write("1e999\n");
    const Received r = read_until_closed(raw.socket, 5s);
    EXPECT_TRUE(r.closed);
    EXPECT_NE(r.text.find(std::to_string(kUnauthorized)), std::string::npos) << r.text;
  }
  e2e::LineConnection c(f.port());
  EXPECT_TRUE(c.call("auth", {{"token", "0123456789abcdef-token"}}).contains("result"));
  EXPECT_TRUE(c.call("echo", {{"n", 1}}).contains("result"));
}

TEST(ConnectionLimits, AnHttpRequestOnTheApiPortIsAnsweredInHttpAndNoLineOfItRuns) {
  HeldCallsServer f;
  RawConnection raw(f.port());
  const std::string body = request_line(1, "echo") + "\n";
  raw.write("POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/plain\r\nContent-Length: " +
            std::to_string(body.size()) + "\r\n\r\n" + body);
  const Received r = read_until_closed(raw.socket, 5s);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.text.rfind("HTTP/1.1 400 Bad Request\r\n", 0), 0u) << r.text;
  EXPECT_NE(r.text.find("JSON-RPC"), std::string::npos);
  EXPECT_EQ(f.calls.load(), 0) << "a line of the HTTP request ran as a call";
}

TEST(ConnectionLimits, ABatchCountsAsItsCallsAndTheNextLineWaitsForThem) {
  ServerLimits limits;
  limits.max_calls_in_progress = 2;
  HeldCallsServer f(limits);
  e2e::LineConnection c(f.port());
  std::string batch = "[";
  for (int k = 1; k <= 5; ++k) batch += (k > 1 ? "," : "") + request_line(k, "slow");
  c.send(batch + "]");
  c.send(request_line(9, "echo"));
  ASSERT_TRUE(f.wait_held(2));
  EXPECT_FALSE(c.next(300ms)) << "the line after the batch ran before the batch's calls started";
  EXPECT_EQ(f.held(), 2u) << "more calls of the batch ran at once than the bound";
  f.release_one();
  ASSERT_TRUE(f.wait_held(2));
  EXPECT_EQ(f.held(), 2u);
  f.release_one();
  f.release_one();
  ASSERT_TRUE(f.wait_held(2));  // the batch's last two: the bound is reached again
  EXPECT_FALSE(c.next(300ms)) << "the line after the batch was read while the bound was reached";
  f.release_one();  // room: the echo is read
  const auto echo = c.next(5s);
  ASSERT_TRUE(echo);
  EXPECT_EQ((*echo)["id"], 9);
  f.release_all();
  const auto answers = c.next(5s);
  ASSERT_TRUE(answers && answers->is_array());
  EXPECT_EQ(answers->size(), 5u);
}

TEST(ConnectionLimits, ABatchLongerThanTheBoundIsRefusedWholeNamingIt) {
  ServerLimits limits;
  limits.max_batch_calls = 3;
  HeldCallsServer f(limits);
  e2e::LineConnection c(f.port());
  c.send("[" + request_line(1, "echo") + "," + request_line(2, "echo") + "," + request_line(3, "echo") + "," +
         request_line(4, "echo") + "]");
  const auto m = c.next(5s);
  ASSERT_TRUE(m);
  EXPECT_EQ((*m)["error"]["code"], kLimitExceeded);
  EXPECT_EQ(limit_of(*m), "max_batch_calls");
  EXPECT_EQ((*m)["error"]["data"]["value"], 3);
  EXPECT_EQ(f.calls.load(), 0);
  EXPECT_TRUE(c.call("echo", json::object()).contains("result")) << "the connection did not go on";
}

TEST(ConnectionLimits, AnAnswerTooLargeBecomesAnErrorNamingTheBoundAndTheConnectionGoesOn) {
  ServerLimits limits;
  limits.max_answer_bytes = 1000;
  HeldCallsServer f(limits);
  e2e::LineConnection c(f.port());
  const json big = c.call("big", {{"n", 2000}});
  EXPECT_EQ(big["error"]["code"], kLimitExceeded) << big.dump().substr(0, 200);
  EXPECT_EQ(limit_of(big), "max_answer_bytes");
  EXPECT_EQ(c.call("big", {{"n", 900}})["result"].get<std::string>().size(), 900u);
  // A batch's answers are one answer: too large together, each call gets the error.
  c.send("[" + request_line(1, "big", {{"n", 600}}) + "," + request_line(2, "big", {{"n", 600}}) + "]");
  const auto batch = c.next(5s);
  ASSERT_TRUE(batch && batch->is_array());
  ASSERT_EQ(batch->size(), 2u);
  EXPECT_EQ((*batch)[0]["id"], 1);
  EXPECT_EQ(limit_of((*batch)[1]), "max_answer_bytes");
}

TEST(ConnectionLimits, AnswersPastTheUnreadOutputBoundBecomeErrorsNotASilentClose) {
  ServerLimits limits;
  limits.max_queued_bytes = 256 << 10;
  HeldCallsServer f(limits);
  RawConnection raw(f.port());
  constexpr int kCalls = 300;  // 30 MB asked for, more than loopback's socket buffers hold
  std::string lines;
  for (int k = 0; k < kCalls; ++k) lines += request_line(k, "big", {{"n", 100000}}) + "\n";
  raw.write(lines);
  std::this_thread::sleep_for(500ms);  // the client reads nothing while the answers are made
  int results = 0, errors = 0;
  std::string buffer;
  while (results + errors < kCalls) {
    pollfd p{raw.socket.native_handle(), POLLIN, 0};
    ASSERT_GT(poll(&p, 1, 10000), 0) << results << " results and " << errors << " errors, then nothing";
    char chunk[65536];
    boost::system::error_code ec;
    buffer.append(chunk, raw.socket.read_some(boost::asio::buffer(chunk), ec));
    ASSERT_FALSE(ec) << "the connection closed after " << results << " results and " << errors << " errors";
    for (std::size_t nl; (nl = buffer.find('\n')) != std::string::npos; buffer.erase(0, nl + 1)) {
      const json m = json::parse(buffer.substr(0, nl));
      if (m.contains("result")) {
        ++results;
      } else {
        EXPECT_EQ(limit_of(m), "max_queued_bytes");
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 0);
  EXPECT_GT(results, 0);
}

TEST(ConnectionLimits, AClientThatSendsNothingIsClosedAtTheFirstRequestDeadlineNamingIt) {
  ServerLimits limits;
  limits.first_request_timeout = Seconds(0.3);
  HeldCallsServer f(limits);
  RawConnection raw(f.port());
  const Received r = read_until_closed(raw.socket, 5s);
  ASSERT_TRUE(r.closed);
  EXPECT_LT(r.after, 2s);
  const json m = json::parse(r.text.substr(0, r.text.find('\n')));
  EXPECT_EQ(m["error"]["code"], kLimitExceeded);
  EXPECT_EQ(limit_of(m), "first_request_timeout");
}

TEST(ConnectionLimits, ARequestLeftUnfinishedIsClosedAtTheRequestDeadline) {
  ServerLimits limits;
  limits.request_timeout = Seconds(0.4);
  HeldCallsServer f(limits);
  RawConnection raw(f.port());
  raw.write(R"({"jsonrpc":"2.0","id":1,"me)");
  const Received r = read_until_closed(raw.socket, 5s);
  ASSERT_TRUE(r.closed);
  EXPECT_EQ(limit_of(json::parse(r.text.substr(0, r.text.find('\n')))), "request_timeout");
}

TEST(ConnectionLimits, AnIdleConnectionIsClosedButOneHoldingASubscriptionIsNot) {
  ServerLimits limits;
  limits.idle_timeout = Seconds(0.5);
  HeldCallsServer f(limits);
  RawConnection idle(f.port()), subscribed(f.port());
  idle.write(request_line(1, "echo") + "\n");
  subscribed.write(request_line(1, "hold") + "\n");
  const Received r = read_until_closed(idle.socket, 5s);
  ASSERT_TRUE(r.closed);
  EXPECT_NE(r.text.find("\"idle_timeout\""), std::string::npos) << r.text;
  const Received kept = read_until_closed(subscribed.socket, 1500ms);
  EXPECT_FALSE(kept.closed) << kept.text;
}

TEST(ConnectionLimits, ConnectionsThatSendNothingDoNotLockAClientOut) {
  ServerLimits limits;
  limits.max_connections = 8;
  limits.first_request_timeout = Seconds(0.5);
  HeldCallsServer f(limits);
  std::vector<std::unique_ptr<RawConnection>> silent;
  for (int k = 0; k < 8; ++k) silent.push_back(std::make_unique<RawConnection>(f.port()));
  {
    RawConnection refused(f.port());
    const Received r = read_until_closed(refused.socket, 5s);
    EXPECT_NE(r.text.find(std::to_string(kServerBusy)), std::string::npos) << r.text;
  }
  // The silent ones' deadline passes; each is closed once its last words are read or within 3 s.
  std::this_thread::sleep_for(4s);
  e2e::LineConnection c(f.port());
  EXPECT_TRUE(c.call("echo", json::object()).contains("result"));
}

}  // namespace
}  // namespace fnet::rpc
