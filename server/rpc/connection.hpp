// A client connection as every transport of the JSON-RPC API keeps it, whatever carries its bytes
// (a TCP stream of lines, rpc_server.hpp; WebSocket messages, server/web): messages in, each run
// through the Handler (a batch answered whole); answers and notifications out through one queue
// per connection, bounded, written one message at a time on the connection's strand.
//
// Everything a client can make the server hold is bounded, in the unit that costs:
// - a message in bytes and in nesting depth while it is parsed; a batch in calls;
// - calls in progress: at most max_calls_in_progress (a batch counts as its calls); the calls
//   beyond wait in the connection's own queue and its input is not read until they have started;
// - output in bytes: an answer larger than max_answer_bytes, or one that would take the unread
//   output past max_queued_bytes, is replaced by an error naming the limit, and the client's input
//   is not read while its unread output is past that bound; subscriptions send
//   only while the unread output is under subscription_window (wait_for_room); a notification
//   past max_queued_bytes ends the connection, with that error as its last words;
// - time: a first message within first_request_timeout, a message begun finished within
//   request_timeout, a connection with nothing in progress and no subscription closed after
//   idle_timeout, output that does not move for write_timeout closes the connection.
// A limit that ends the connection says so first, with error -32008 naming it (data.limit).
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it
#include <vector>

#include <boost/asio.hpp>

#include "proto/json_rpc.hpp"
#include "server/rpc/access.hpp"
#include "server/rpc/peer.hpp"
#include "server/rpc/server_limits.hpp"

namespace fnet::rpc {

// The strand a connection's socket and handlers run on (of an io_context, so that Beast's
// operations can be bound to it).
using Strand = boost::asio::strand<boost::asio::io_context::executor_type>;

class Connection : public Peer, public std::enable_shared_from_this<Connection> {
 public:
  ~Connection() override;

  // Starts reading, and the connection's deadlines, on its strand.
  void start();
  bool send(const json& message) final;
  bool wait_for_room(std::function<void()> resume) final;
  void subscriptions_changed(int delta) final;
  std::uint64_t id() const final { return id_; }
  void on_close(std::function<void()> fn) final;

 protected:
  // `terminator` ends each message on the wire ("\n" for lines; none where the transport frames
  // messages); `on_end` runs when the connection is destroyed.
  // `strand` is the one the socket was accepted on. Until a connection has presented the token
  // `access` asks for (`authenticated` false), its first message must be the auth request.
  Connection(Strand strand, std::string terminator, const ServerLimits& limits, const Handler& handler,
             const Access& access, bool authenticated, std::function<void()> on_end);

  // The transport's part, each called on the strand:
  virtual void read_next() = 0;                     // reads one message, then take_message() or an end below
  virtual void write(const std::string& text) = 0;  // writes one queued message, then calls written()
  virtual bool is_open() const = 0;
  virtual bool partial_input() const = 0;  // part of a message has been received
  virtual void finish() = 0;               // after the last reply: closes in order, then close()
  virtual void close_transport() = 0;      // closes at once

  // What the transport reports, on the strand:
  // One message read: a request or a batch; blank text is ignored. Reads on unless calls wait.
  void take_message(std::string_view text);
  // The client sent `error` (a message too long to read, say): it is sent, then the connection finishes.
  void refuse(const json& error);
  // The same with text of the transport's own (an HTTP response to an HTTP request, say).
  void refuse_text(std::string text);
  // The client is done sending: what it asked is answered, then the connection closes.
  void input_ended();
  // The write of the front message ended.
  void written(const boost::system::error_code& ec);
  // Ends the connection now; its close callbacks run.
  void close();

  Strand strand_;
  const ServerLimits& limits_;

 private:
  struct Call {
    json request;
    std::function<void(json)> reply;
  };
  using Clock = std::chrono::steady_clock;

  // Runs one message; false when it refused the connection (no token presented).
  bool run_message(std::string_view text);
  // The transports' own method, answered here and never by the Handler: auth presents the token.
  void answer_auth(const json& request);
  // Starts waiting calls while fewer than max_calls_in_progress are; on the strand.
  void start_calls();
  void end_call();
  // After a call ended, on the strand: the next calls start, reading resumes, or the connection
  // finishes once nothing is left to answer.
  void after_call();
  // Reads the next message when no call waits and there is room for more in progress.
  void read_if_room();
  void write_next();
  std::size_t window() const;
  // The deadlines, checked once a tick on the strand.
  void tick();
  // Ends the connection for the deadline `limit` passed, telling the client.
  void expire(const char* limit, Seconds value, const std::string& message);

  const std::string terminator_;
  const Handler& handler_;
  const Access& access_;
  bool authenticated_;  // read and written on the strand
  std::function<void()> on_end_;
  boost::asio::steady_timer ticker_;
  const std::chrono::steady_clock::time_point opened_ = std::chrono::steady_clock::now();

  // On the strand only:
  std::deque<Call> waiting_;  // calls read and not yet started, in order
  bool starting_ = false;     // start_calls() is running (a call it starts may end at once)
  bool reading_ = false;      // a read of the next message is in progress
  bool got_message_ = false;
  std::optional<Clock::time_point> input_since_;  // when the message being read began

  std::mutex mutex_;  // guards what follows (send() and end_call() run on any thread)
  std::deque<std::string> output_;
  std::size_t queued_bytes_ = 0;
  bool writing_ = false;
  bool close_when_flushed_ = false;
  std::size_t in_progress_ = 0;  // calls started whose answer is not yet queued
  int subscriptions_ = 0;
  std::function<void()> resume_;  // wait_for_room's, called once the output drains
  Clock::time_point last_activity_ = Clock::now();
  Clock::time_point last_write_ = Clock::now();
  std::vector<std::function<void()>> close_callbacks_;
  std::atomic<bool> closed_{false};
  std::uint64_t id_;
};

}  // namespace fnet::rpc
