// fnet-server's command line: what it serves, where, and the limits it serves within.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <variant>

#include "server/rpc/server_limits.hpp"

namespace fnet::server {

struct ServerOptions {
  std::string data_dir, bind = "127.0.0.1";
  unsigned short port = 7707;
  std::optional<unsigned short> http_port;  // the dashboard's; none: not served
  std::string token;                        // asked of every connection (--token-file); empty: none
  std::string token_file;                   // where the token is; beyond loopback without one: DATA_DIR/token
  std::string tls_cert, tls_key;            // PEM files; both empty: no TLS
  unsigned threads = 1;                     // analysis threads, >= 1; the default is the hardware's
  int domain = 0;                           // DDS domain id
  std::size_t max_in_flight = 64, max_subscriptions = 16;
  rpc::ServerLimits limits;  // of every API connection, TCP and WebSocket
  // Frames: the bytes held for analysis at once, the largest frame, and contacts per grain
  // (contact_degeneracy; 0: no bound).
  std::size_t max_in_flight_mib = 256, max_frame_mib = 64, max_contacts_per_grain = 24;
  std::size_t cache_mib = 64;  // the bound of the diagrams and networks read back from the stores
  double gap_timeout = 30;     // seconds
  double store_retry = 2;      // seconds between retries of a store that cannot be written
  double store_idle = 600;     // seconds without writes after which a run's store is closed
  double stop_timeout = 5;     // seconds a stop waits for the analysis in progress
  // Seconds a store found in the data directory has to pass its check before it is refused.
  double store_check_seconds = 30;
};

// The options, or the exit code when the program ends here: 0 after printing --help or
// --version, 2 after a usage error (its message on stderr).
std::variant<ServerOptions, int> parse_server_options(int argc, char** argv);

}  // namespace fnet::server
