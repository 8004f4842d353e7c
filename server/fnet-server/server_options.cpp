#include "server/fnet-server/server_options.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>

#include <boost/asio/ip/address.hpp>
#include <boost/program_options.hpp>

#include "common/build_info/build_info.hpp"
#include "server/rpc/access.hpp"

namespace po = boost::program_options;

namespace fnet::server {

namespace {

// A limit in seconds, set through its option.
po::typed_value<double>* seconds(rpc::Seconds& limit) {
  return po::value<double>()->default_value(limit.count())->notifier([&limit](double s) {
    if (!(s > 0)) throw po::error("a timeout must be a positive number of seconds");
    limit = rpc::Seconds(s);
  });
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
      "write-timeout", seconds(l.write_timeout), "seconds queued output may stay unread before the client is dropped");
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
      "frames held for analysis at once; beyond it DDS makes the simulation wait (about 150 KB per "
      "2 000-particle frame, counted twice: here and in the DDS reader)")(
      "gap-timeout", po::value(&o.gap_timeout)->default_value(o.gap_timeout),
      "seconds to wait for a missing frame before skipping it")(
      "max-subscriptions", po::value(&o.max_subscriptions)->default_value(o.max_subscriptions),
      "subscriptions per connection");
  add_limit_options(options, o.limits);
  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, options), vm);
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
    if (o.threads == 0 || o.max_in_flight == 0) throw po::error("--threads and --max-in-flight must be positive");
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
