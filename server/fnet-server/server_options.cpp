#include "server/fnet-server/server_options.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include <boost/asio/ip/address.hpp>
#include <boost/program_options.hpp>

#include "common/build_info/build_info.hpp"
#include "common/codec/command_line.hpp"
#include "server/rpc/access.hpp"

namespace po = boost::program_options;

namespace fnet::server {
namespace {

constexpr std::size_t kMaxMib = std::size_t{1} << 20;  // MiB counts stay far from overflowing in bytes

// A limit in seconds, set through its option (checked with the others after parsing).
po::typed_value<double>* seconds(rpc::Seconds& limit) {
  return po::value<double>()->default_value(limit.count())->notifier([&limit](double s) { limit = rpc::Seconds(s); });
}

// What one client may make the server hold (proto/api.md, Limits).
void add_limit_options(po::options_description& options, rpc::ServerLimits& l) {
  options.add_options()("max-connections", po::value(&l.max_connections)->default_value(l.max_connections),
                        "concurrent API connections (TCP; the dashboard's are counted apart)")(
      "max-line-bytes", po::value(&l.max_line_bytes)->default_value(l.max_line_bytes),
      "longest request line (WebSocket message) accepted")(
      "max-batch-calls", po::value(&l.max_batch_calls)->default_value(l.max_batch_calls), "calls in one batch")(
      "max-queued-bytes", po::value(&l.max_queued_bytes)->default_value(l.max_queued_bytes),
      "unread output per connection; an answer beyond it is replaced by an error")(
      "max-answer-bytes", po::value(&l.max_answer_bytes)->default_value(l.max_answer_bytes),
      "largest answer sent; a larger one is replaced by an error")(
      "first-request-timeout", seconds(l.first_request_timeout),
      "seconds a new connection has to send its first request (auth, with a token)")(
      "request-timeout", seconds(l.request_timeout), "seconds from a request's first byte to its last")(
      "idle-timeout", seconds(l.idle_timeout),
      "seconds after which a connection with nothing in progress and no subscription is closed")(
      "write-timeout", seconds(l.write_timeout), "seconds queued output may stay unread before the client is dropped")(
      "max-call-seconds", seconds(l.max_call_seconds),
      "seconds of computation one heavy call (distance.get, blocks.get, network.get) may take; past it the call "
      "is stopped and answered with an error");
}

}  // namespace

std::variant<ServerOptions, int> parse_server_options(int argc, char** argv) {
  ServerOptions o;
  o.threads = std::max(1u, std::thread::hardware_concurrency());
  po::options_description options(
      "usage: fnet-server --data-dir DIR [--port P] [options]\n\n"
      "Analyzes force-network frames streamed over Cyclone DDS (topics fnet_RunInfo, fnet_ForceFrame;\n"
      "set CYCLONEDDS_URI, e.g. to deploy/cyclonedds-loopback.xml) and serves the results as\n"
      "newline-delimited JSON-RPC 2.0 over TCP (proto/api.md). One HDF5 store per run in DIR;\n"
      "on restart the stores are reloaded and runs still streaming continue.\n\noptions");
  options.add_options()("help,h", "show this help")("version", "print the version and commit, then exit")(
      "data-dir", po::value(&o.data_dir)->required(), "directory of the run stores (created if absent)")(
      "port", po::value(&o.port)->default_value(o.port),
      "TCP port of the JSON API (0: any free port, printed at start)")(
      "bind", po::value(&o.bind)->default_value(o.bind), "address to listen on (loopback by default)")(
      "http-port", po::value<unsigned short>(),
      "TCP port of the dashboard: the page and the JSON API over a WebSocket, on the --bind address (0: any "
      "free port, printed at start; default: no dashboard)")(
      "token-file", po::value<std::string>(),
      "a file holding the token every connection to the API and the dashboard must present (one line, 16 or more "
      "of A-Z a-z 0-9 . _ ~ -); beyond loopback without it, DATA_DIR/token is made (mode 0600) and used")(
      "tls-cert", po::value(&o.tls_cert),
      "PEM certificate chain: the API and the dashboard speak TLS (required to --bind any address but loopback)")(
      "tls-key", po::value(&o.tls_key), "PEM private key of --tls-cert")(
      "threads", po::value(&o.threads)->default_value(o.threads), "analysis threads")(
      "domain", po::value(&o.domain)->default_value(o.domain), "DDS domain id")(
      "max-in-flight", po::value(&o.max_in_flight)->default_value(o.max_in_flight),
      "frames held for analysis at once; beyond it DDS makes the simulation wait (about 200 KB per "
      "2 000-particle frame)")("max-in-flight-mib", po::value(&o.max_in_flight_mib)->default_value(o.max_in_flight_mib),
                               "MiB of frames held for analysis at once (32 bytes per grain and per contact); beyond "
                               "it DDS makes the simulation wait, and the DDS reader holds about as much again")(
      "max-frame-mib", po::value(&o.max_frame_mib)->default_value(o.max_frame_mib),
      "largest frame analyzed, in MiB (32 bytes per grain and per contact: 64 MiB is a million of each); a larger "
      "frame is rejected unread, with its reason")(
      "cache-mib", po::value(&o.cache_mib)->default_value(o.cache_mib),
      "MiB of diagrams and force networks read back from the run stores, kept for the next request, least "
      "recently used dropped first, shared by every run; memory holds each committed frame's row only (0: no "
      "cache, every request reads the store)")(
      "max-contacts-per-grain", po::value(&o.max_contacts_per_grain)->default_value(o.max_contacts_per_grain),
      "a frame whose grains, taken one at a time, each touch more than this many grains not yet taken (its contact "
      "graph's degeneracy) is rejected unanalyzed; grains that do not overlap reach 5 (disks) or 12 (spheres) "
      "whatever their sizes (0: no bound)")("gap-timeout", po::value(&o.gap_timeout)->default_value(o.gap_timeout),
                                            "seconds to wait for a missing frame before skipping it")(
      "store-retry", po::value(&o.store_retry)->default_value(o.store_retry),
      "seconds between retries of a run's store that cannot be written (a full disk, no file descriptor left); "
      "its frames wait in memory, counted with --max-in-flight")(
      "store-idle", po::value(&o.store_idle)->default_value(o.store_idle),
      "seconds without a write after which a run's store is closed (a run whose planned frames are all settled is "
      "closed at once); a closed store is read on demand and reopened by the run's next frame")(
      "stop-timeout", po::value(&o.stop_timeout)->default_value(o.stop_timeout),
      "seconds SIGTERM waits for the frames in analysis before it abandons them (the stores keep what was "
      "committed; publishers still running send the rest again after a restart)")(
      "store-check-seconds", po::value(&o.store_check_seconds)->default_value(o.store_check_seconds),
      "seconds a store found in DIR (at start, or by server.rescan) has to be read whole by a process of its own "
      "before the server reads it; a store whose check fails or takes longer is refused, with its reason (HDF5 "
      "may loop forever on a damaged file)")("max-subscriptions",
                                             po::value(&o.max_subscriptions)->default_value(o.max_subscriptions),
                                             "subscriptions per connection");
  add_limit_options(options, o.limits);
  try {
    po::variables_map vm;
    const po::parsed_options parsed = po::parse_command_line(argc, argv, options);
    refuse_stray_arguments(parsed);
    po::store(parsed, vm);
    if (vm.count("help")) {
      std::cout << options << "\n";
      return 0;
    }
    if (vm.count("version")) {
      std::cout << fnet::version_line("fnet-server") << "\n";
      return 0;
    }
    po::notify(vm);
    if (vm.count("http-port")) o.http_port = vm["http-port"].as<unsigned short>();
    if (vm.count("token-file")) {
      o.token_file = vm["token-file"].as<std::string>();
      try {
        o.token = fnet::rpc::read_token_file(o.token_file);
      } catch (const std::runtime_error& e) {
        throw po::error(std::string("--token-file: ") + e.what());
      }
    }
    if (o.threads == 0 || o.max_in_flight == 0 || o.max_in_flight_mib == 0 || o.max_frame_mib == 0)
      throw po::error("--threads, --max-in-flight, --max-in-flight-mib and --max-frame-mib must be positive");
    if (o.max_in_flight_mib > kMaxMib || o.max_frame_mib > kMaxMib || o.cache_mib > kMaxMib)
      throw po::error("--max-in-flight-mib, --max-frame-mib and --cache-mib must be at most " +
                      std::to_string(kMaxMib) + " (1 TiB)");
    const rpc::ServerLimits& l = o.limits;
    for (const auto& [flag, seconds] :
         {std::pair{"--store-retry", o.store_retry}, std::pair{"--store-idle", o.store_idle},
          std::pair{"--stop-timeout", o.stop_timeout}, std::pair{"--store-check-seconds", o.store_check_seconds},
          std::pair{"--first-request-timeout", l.first_request_timeout.count()},
          std::pair{"--request-timeout", l.request_timeout.count()},
          std::pair{"--idle-timeout", l.idle_timeout.count()}, std::pair{"--write-timeout", l.write_timeout.count()},
          std::pair{"--max-call-seconds", l.max_call_seconds.count()}})
      if (!(seconds > 0 && seconds <= 1e6))
        throw po::error(std::string(flag) + " must be a number of seconds above 0 and at most 1e6");
    boost::system::error_code bad_address;
    boost::asio::ip::make_address(o.bind, bad_address);
    if (bad_address) throw po::error("--bind '" + o.bind + "' is not an IP address");
    if (o.tls_cert.empty() != o.tls_key.empty()) throw po::error("--tls-cert and --tls-key go together");
    // Never an open API or dashboard on a network: beyond loopback, only holders of the token, and
    // only over TLS, so that neither the token nor the results travel in clear.
    if (!fnet::rpc::is_loopback(o.bind) && o.tls_cert.empty())
      throw po::error("--bind " + o.bind +
                      " is not a loopback address: give --tls-cert FILE --tls-key FILE, so that the API and the "
                      "dashboard speak TLS");
    if (!fnet::rpc::is_loopback(o.bind) && o.token_file.empty())
      o.token_file = (std::filesystem::path(o.data_dir) / "token").string();
  } catch (const po::error& e) {
    std::cerr << "fnet-server: " << e.what() << " (see --help)\n";
    return 2;
  }
  return o;
}

}  // namespace fnet::server
