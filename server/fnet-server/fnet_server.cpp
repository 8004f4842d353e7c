// fnet-server: subscribes to the frames of every run on DDS, analyzes them as they arrive, keeps
// one store per run under --data-dir and answers JSON-RPC on 127.0.0.1 (proto/api.md); with
// --http-port, the dashboard too (server/web).
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>

#include "server/api/api_methods.hpp"
#include "server/fnet-server/server_options.hpp"
#include "server/fnet-server/token_file.hpp"
#include "server/registry/ingest.hpp"
#include "server/registry/run_registry.hpp"
#include "server/rpc/rpc_server.hpp"
#include "server/web/http_server.hpp"

namespace {

using namespace fnet::server;

RegistryLimits registry_limits(const ServerOptions& o) {
  RegistryLimits limits;
  limits.gap_timeout = std::chrono::milliseconds(static_cast<long>(o.gap_timeout * 1000));
  return limits;
}

// The address a browser opens: an IPv6 address in brackets.
std::string dashboard_address(const std::string& bind, unsigned short port, bool tls) {
  const std::string host = bind.find(':') == std::string::npos ? bind : "[" + bind + "]";
  return (tls ? "https://" : "http://") + host + ":" + std::to_string(port) + "/";
}

// Reopens the stores under --data-dir; a store that cannot be loaded is reported and left out.
void load_stores(Registry& registry) {
  for (const std::string& problem : registry.load())
    std::cerr << "fnet-server: could not load a store: " << problem << "\n";
}

// Answers on two threads (a slow query never stalls every client) until SIGINT or SIGTERM.
void serve_until_signalled(boost::asio::io_context& io, fnet::rpc::Server& server,
                           std::optional<fnet::web::HttpServer>& dashboard) {
  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code&, int) {
    server.stop();
    if (dashboard) dashboard->stop();
    io.stop();
  });
  std::thread second([&io] { io.run(); });
  io.run();
  second.join();
}

}  // namespace

int main(int argc, char** argv) {
  const auto parsed = parse_server_options(argc, argv);
  if (const int* exit_code = std::get_if<int>(&parsed)) return *exit_code;
  ServerOptions o = std::get<ServerOptions>(parsed);
  try {
    if (o.token.empty() && !o.token_file.empty()) {  // beyond loopback, given none: made (or kept) in DATA_DIR
      std::filesystem::create_directories(o.data_dir);
      o.token = ensure_token_file(o.token_file);
      std::cout << "fnet-server token in " << o.token_file << " (mode 0600; clients: --token-file or FNET_TOKEN)"
                << std::endl;
    }
    const fnet::rpc::TlsContext tls = o.tls_cert.empty() ? nullptr : fnet::rpc::make_server_tls(o.tls_cert, o.tls_key);
    boost::asio::thread_pool pool(o.threads);
    Registry registry(o.data_dir, pool, registry_limits(o));
    load_stores(registry);
    boost::asio::io_context io;
    ApiContext context{registry};
    context.max_subscriptions_per_connection = o.max_subscriptions;
    context.offload = [&pool](std::function<void()> work) { boost::asio::post(pool, std::move(work)); };
    const fnet::rpc::Handler api = make_api(context);
    const fnet::rpc::Access access{o.token};
    fnet::rpc::Server server(io, o.bind, o.port, api, o.limits, access, tls);
    std::optional<fnet::web::HttpServer> dashboard;
    if (o.http_port) dashboard.emplace(io, o.bind, *o.http_port, api, o.limits, access, tls);
    context.connections = [&server, &dashboard] {
      return server.connections() + (dashboard ? dashboard->connections() : 0);
    };
    Ingest ingest(registry, {static_cast<dds_domainid_t>(o.domain), o.max_in_flight});
    context.ingest_state = [&ingest] { return ingest.state(); };
    std::cout << "fnet-server listening on " << o.bind << ":" << server.port() << (tls ? " (TLS)" : "") << " data-dir "
              << o.data_dir << std::endl;
    if (dashboard)
      std::cout << "fnet-server dashboard on " << dashboard_address(o.bind, dashboard->port(), tls != nullptr)
                << std::endl;
    serve_until_signalled(io, server, dashboard);
    ingest.stop();
    pool.join();  // finish what was taken, so the stores hold it
    std::cerr << "fnet-server: stopped\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "fnet-server: " << e.what() << "\n";
    return 1;
  }
}
