// fnet-server: subscribes to the frames of every run on DDS, analyzes them as they arrive, keeps
// one store per run under --data-dir and answers JSON-RPC on 127.0.0.1 (proto/api.md).
#include <iostream>
#include <thread>

#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/program_options.hpp>

#include "common/build_info/build_info.hpp"
#include "server/api/api_methods.hpp"
#include "server/registry/ingest.hpp"
#include "server/registry/run_registry.hpp"
#include "server/rpc/rpc_server.hpp"

namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string data_dir, bind = "127.0.0.1";
  unsigned short port = 7707;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  int domain = 0;
  std::size_t max_in_flight = 64, max_connections = 256, max_line = 1 << 20, max_subscriptions = 16,
              max_queued = 16 << 20;
  double gap_timeout = 30;
  po::options_description options(
      "usage: fnet-server --data-dir DIR [--port P] [options]\n\n"
      "Analyzes force-network frames streamed over Cyclone DDS (topics fnet_RunInfo, fnet_ForceFrame;\n"
      "set CYCLONEDDS_URI, e.g. to deploy/cyclonedds-loopback.xml) and serves the results as\n"
      "newline-delimited JSON-RPC 2.0 over TCP (proto/api.md). One HDF5 store per run in DIR;\n"
      "on restart the stores are reloaded and runs still streaming continue.\n\noptions");
  options.add_options()("help,h", "show this help")("version", "print the version and commit, then exit")(
      "data-dir", po::value(&data_dir)->required(), "directory of the run stores (created if absent)")(
      "port", po::value(&port)->default_value(port), "TCP port of the JSON API (0: any free port, printed at start)")(
      "bind", po::value(&bind)->default_value(bind), "address to listen on (loopback by default)")(
      "threads", po::value(&threads)->default_value(threads), "analysis threads")(
      "domain", po::value(&domain)->default_value(domain), "DDS domain id")(
      "max-in-flight", po::value(&max_in_flight)->default_value(max_in_flight),
      "frames held for analysis at once; beyond it DDS makes the simulation wait (about 150 KB per "
      "2 000-particle frame, counted twice: here and in the DDS reader)")(
      "gap-timeout", po::value(&gap_timeout)->default_value(gap_timeout),
      "seconds to wait for a missing frame before skipping it")(
      "max-connections", po::value(&max_connections)->default_value(max_connections), "concurrent API connections")(
      "max-line-bytes", po::value(&max_line)->default_value(max_line), "longest request line accepted")(
      "max-subscriptions", po::value(&max_subscriptions)->default_value(max_subscriptions),
      "subscriptions per connection")("max-queued-bytes", po::value(&max_queued)->default_value(max_queued),
                                      "output queued for a client that does not read, beyond which it is dropped");
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
    if (threads == 0 || max_in_flight == 0) throw po::error("--threads and --max-in-flight must be positive");
    boost::system::error_code bad_address;
    boost::asio::ip::make_address(bind, bad_address);
    if (bad_address) throw po::error("--bind '" + bind + "' is not an IP address");
  } catch (const po::error& e) {
    std::cerr << "fnet-server: " << e.what() << " (see --help)\n";
    return 2;
  }

  try {
    boost::asio::thread_pool pool(threads);
    fnet::server::RegistryLimits limits;
    limits.gap_timeout = std::chrono::milliseconds(static_cast<long>(gap_timeout * 1000));
    fnet::server::Registry registry(data_dir, pool, limits);
    for (const std::string& problem : registry.load())
      std::cerr << "fnet-server: could not load a store: " << problem << "\n";

    boost::asio::io_context io;
    fnet::server::ApiContext context{registry};
    context.max_subscriptions_per_connection = max_subscriptions;
    context.offload = [&pool](std::function<void()> work) { boost::asio::post(pool, std::move(work)); };
    fnet::rpc::ServerLimits rpc_limits;
    rpc_limits.max_connections = max_connections;
    rpc_limits.max_line_bytes = max_line;
    rpc_limits.max_queued_bytes = max_queued;
    fnet::rpc::Server server(io, bind, port, fnet::server::make_api(context), rpc_limits);
    context.connections = [&server] { return server.connections(); };

    fnet::server::Ingest ingest(registry, {static_cast<dds_domainid_t>(domain), max_in_flight});
    context.ingest_state = [&ingest] { return ingest.state(); };
    std::cout << "fnet-server listening on " << bind << ":" << server.port() << " data-dir " << data_dir << std::endl;

    boost::asio::signal_set signals(io, SIGINT, SIGTERM);
    signals.async_wait([&](const boost::system::error_code&, int) {
      server.stop();
      io.stop();
    });
    std::thread second([&io] { io.run(); });  // a slow query never stalls every client
    io.run();
    second.join();
    ingest.stop();
    pool.join();  // finish what was taken, so the stores hold it
    std::cerr << "fnet-server: stopped\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "fnet-server: " << e.what() << "\n";
    return 1;
  }
}
