// What one client may make fnet-server hold, in the unit that costs: bytes, calls, seconds. One
// list of the limits: fnet-server's options set them (server_options.cpp) and proto/api.md's
// Limits table names each by its key here, as errors -32008 do in data.limit.
#pragma once

#include <chrono>
#include <cstddef>

namespace fnet::rpc {

using Seconds = std::chrono::duration<double>;

struct ServerLimits {
  std::size_t max_line_bytes = 1 << 20;         // a longer message gets an error and the connection closes
  std::size_t max_json_depth = 64;              // arrays and objects nested deeper: error -32008
  std::size_t max_batch_calls = 100;            // a longer batch: error -32008, none of it runs
  std::size_t max_connections = 256;            // beyond: an error line, then close
  std::size_t max_calls_in_progress = 32;       // per connection; a batch counts as its calls
  std::size_t max_queued_bytes = 16 << 20;      // unread output; an answer past it becomes an error
  std::size_t max_answer_bytes = 8 << 20;       // one answer (a batch's: all of it) larger: an error in its place
  std::size_t subscription_window = 256 << 10;  // subscriptions wait while more output is unread
  Seconds first_request_timeout{10};            // from the connection to its first message
  Seconds request_timeout{30};                  // from a message's first byte to its last
  Seconds idle_timeout{600};                    // nothing in progress, no subscription, nothing received
  Seconds write_timeout{60};                    // queued output that does not move
  Seconds max_call_seconds{60};                 // a heavy call's computation, stopped past it (server/api)
};

}  // namespace fnet::rpc
