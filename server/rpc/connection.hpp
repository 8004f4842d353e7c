// A client connection as every transport of the JSON-RPC API keeps it, whatever carries its bytes
// (a TCP stream of lines, rpc_server.hpp; WebSocket messages, server/web): messages in, each run
// through the Handler (a batch answered whole); answers and notifications out through one queue
// per connection, bounded, written one message at a time on the connection's strand.
// Everything a client can make the server hold is bounded: calls unanswered at once (beyond, its
// input waits) and bytes queued for a client that does not read (that client is dropped).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it
#include <vector>

#include <boost/asio.hpp>

#include "proto/json_rpc.hpp"
#include "server/rpc/access.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::rpc {

struct ServerLimits {
  std::size_t max_line_bytes = 1 << 20;     // a longer request gets an error and the connection closes
  std::size_t max_connections = 256;        // beyond: an error line, then close
  std::size_t max_queued_bytes = 16 << 20;  // unread output beyond this drops the client
  std::size_t max_pending_calls = 32;       // calls of one connection unanswered at once; beyond, its input waits
};

// The strand a connection's socket and handlers run on (of an io_context, so that Beast's
// operations can be bound to it).
using Strand = boost::asio::strand<boost::asio::io_context::executor_type>;

class Connection : public Peer, public std::enable_shared_from_this<Connection> {
 public:
  ~Connection() override;

  // Starts reading on the connection's strand.
  void start();
  // Drops the client when its unread output exceeds max_queued_bytes.
  bool send(const json& message) final;
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
  virtual void finish() = 0;           // after the last reply: closes in order, then close()
  virtual void close_transport() = 0;  // closes at once

  // What the transport reports, on the strand:
  // One message read: a request or a batch; blank text is ignored. Reads on unless the calls
  // unanswered reached their bound (reading resumes when one ends).
  void take_message(std::string_view text);
  // The client sent `error` (a message too long to read): it is sent, then the connection finishes.
  void refuse(const json& error);
  // The client is done sending: what it asked is answered, then the connection closes.
  void input_ended();
  // The write of the front message ended.
  void written(const boost::system::error_code& ec);
  // Ends the connection now; its close callbacks run.
  void close();

  Strand strand_;
  const ServerLimits& limits_;

 private:
  // Runs one message; false when it refused the connection (no token presented).
  bool run_message(std::string_view text);
  // The transports' own method, answered here and never by the Handler: auth presents the token.
  void answer_auth(const json& request);
  void begin_call();
  void end_call();
  void write_next();

  const std::string terminator_;
  const Handler& handler_;
  const Access& access_;
  bool authenticated_;  // read and written on the strand
  std::function<void()> on_end_;
  std::mutex mutex_;  // guards the output queue and close callbacks (send() is called from any thread)
  std::deque<std::string> output_;
  std::size_t queued_bytes_ = 0;
  bool writing_ = false;
  bool close_when_flushed_ = false;
  std::size_t pending_calls_ = 0;  // requests (a batch counts once) whose answer is not yet queued
  bool read_paused_ = false;       // reading waits for a call to end
  std::vector<std::function<void()>> close_callbacks_;
  std::atomic<bool> closed_{false};
  std::uint64_t id_;
};

}  // namespace fnet::rpc
