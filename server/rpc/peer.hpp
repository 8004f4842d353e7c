// What the methods know of the client that called them, whatever carries its messages (a TCP
// connection, rpc_server.hpp; the next transport another implementation): it takes messages at
// any time from any thread, has an id, and says when it ends.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>

#include "proto/json_rpc.hpp"

namespace fnet::rpc {

class Peer {
 public:
  virtual ~Peer() = default;
  // Queues one JSON message; thread-safe and never blocks. An answer the transport's bounds do not
  // admit is replaced by an error that names the bound. Returns false once the peer is closed.
  virtual bool send(const json& message) = 0;
  // Unique among the peers of this process.
  virtual std::uint64_t id() const = 0;
  // Called once when the peer ends; at once when it has ended.
  virtual void on_close(std::function<void()> fn) = 0;
  // For what is sent unasked (a subscription's points): true when the peer has room for more now;
  // otherwise false, and `resume` is called once when it has (never after the peer has closed;
  // a later call replaces an earlier `resume`). Thread-safe; `resume` runs on the peer's thread.
  virtual bool wait_for_room(std::function<void()> resume) = 0;
  // The subscriptions the peer holds went up or down by `delta`: a peer that holds one is not idle.
  virtual void subscriptions_changed(int delta) = 0;
};

// How a call ends: its result, or the exception it ended with (rpc::Error for the caller's
// mistakes; any other is an internal error).
using Completion = std::function<void(json result, std::exception_ptr error)>;

// The methods as every transport calls them: on a transport's thread, for each well-formed
// request. The handler calls `done` exactly once: at once, or later from another thread (a heavy
// method's work runs on the analysis pool), so answers may leave in another order than the
// requests came in; the caller matches them by id. A handler that throws has ended the call with
// that exception. Methods see the caller as a Peer only.
using Handler = std::function<void(const std::string& method, const json& params, const std::shared_ptr<Peer>& peer,
                                   Completion done)>;

}  // namespace fnet::rpc
