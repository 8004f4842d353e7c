// fnet-server: subscribes to the frames of every run on DDS, analyzes them as they arrive, keeps
// one store per run under --data-dir and answers JSON-RPC on 127.0.0.1 (proto/api.md); with
// --http-port, the dashboard too (server/web).
#include <malloc.h>
#include <unistd.h>

#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <boost/asio/signal_set.hpp>

#include "server/api/api_methods.hpp"
#include "server/fnet-server/server_options.hpp"
#include "server/fnet-server/store_check_command.hpp"
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
  limits.store_retry = std::chrono::milliseconds(static_cast<long>(o.store_retry * 1000));
  limits.store_idle = std::chrono::milliseconds(static_cast<long>(o.store_idle * 1000));
  limits.max_contacts_per_grain = o.max_contacts_per_grain;
  limits.store_check = StoreCheckOptions{check_store_command(), o.store_check_seconds, o.threads};
  limits.cache_bytes = o.cache_mib << 20;
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

// How this server names itself to the publishers (fnet_RunStatus): host, process, data directory.
std::string server_name(const std::string& data_dir) {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  return std::string(host) + ":" + std::to_string(getpid()) + ":" + data_dir;
}

// A thread that tends the stores four times a second (Registry::tend_stores) and tells the
// publishers each run's status that changed, until destroyed. Every kTrimTicks ticks it gives
// the pages malloc holds free back to the system (malloc_trim): what one thread frees of what
// another allocated (the frame cache's entries, above all) otherwise stays resident in the
// allocating thread's arena.
class StoreTending {
 public:
  static constexpr unsigned kTrimTicks = 8;
  StoreTending(Registry& registry, Ingest& ingest, std::string server)
      : thread_([this, &registry, &ingest, server = std::move(server)] {
          std::unique_lock lock(mutex_);
          for (unsigned tick = 1; !cv_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stop_; });
               ++tick) {
            lock.unlock();
            if (tick % kTrimTicks == 0) malloc_trim(0);
            try {
              for (fnet::RunStatus& status : registry.tend_stores()) {
                status.server = server;
                ingest.publish_status(status);
              }
            } catch (const std::exception& e) {
              std::cerr << "fnet-server: run status not published: " << e.what() << "\n";
            }
            lock.lock();
          }
        }) {}
  ~StoreTending() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;  // last: started once the rest exists
};

// Waits up to `seconds` for the analysis in progress. Past them, drops the jobs not started,
// writes out what was committed, closes the stores and ends the process without waiting for the
// jobs still running (their frames are not in the stores: publishers still running send them
// again after a restart, from the history they keep).
void stop_within(boost::asio::thread_pool& pool, Registry& registry, double seconds) {
  std::promise<void> joined;
  std::future<void> done = joined.get_future();
  std::thread joiner([&pool, &joined] {
    pool.join();
    joined.set_value();
  });
  if (done.wait_for(std::chrono::duration<double>(seconds)) == std::future_status::ready) {
    joiner.join();
    return;
  }
  pool.stop();
  registry.seal_stores();
  std::cerr << "fnet-server: stopped after --stop-timeout " << seconds
            << " s: frames still in analysis were abandoned (not stored; received again after a restart)" << std::endl;
  std::cout.flush();
  std::_Exit(0);
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
  if (const std::optional<int> checked = run_check_store(argc, argv)) return *checked;
  const auto parsed = parse_server_options(argc, argv);
  if (const int* exit_code = std::get_if<int>(&parsed)) return *exit_code;
  ServerOptions o = std::get<ServerOptions>(parsed);
  // Beyond a file-size limit a write fails (a store fault, retried) instead of killing the server.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    if (o.token.empty() && !o.token_file.empty()) {  // beyond loopback, given none: made (or kept) in DATA_DIR
      std::filesystem::create_directories(o.data_dir);
      o.token = ensure_token_file(o.token_file);
      std::cout << "fnet-server token in " << o.token_file << " (mode 0600; clients: --token-file or FNET_TOKEN)"
                << std::endl;
    }
    const fnet::rpc::TlsContext tls = o.tls_cert.empty() ? nullptr : fnet::rpc::make_server_tls(o.tls_cert, o.tls_key);
    boost::asio::thread_pool pool(o.threads);
    // The runs' analysis and the API's heavy queries share the pool, served in turn.
    FairScheduler scheduler(pool, o.threads);
    Registry registry(o.data_dir, scheduler, registry_limits(o));
    load_stores(registry);
    boost::asio::io_context io;
    ApiContext context{registry};
    context.max_subscriptions_per_connection = o.max_subscriptions;
    context.max_call_seconds = o.limits.max_call_seconds;
    context.offload = [&scheduler](std::function<void()> work) { scheduler.post(kApiQueue, std::move(work)); };
    const fnet::rpc::Handler api = make_api(context);
    const fnet::rpc::Access access{o.token};
    fnet::rpc::Server server(io, o.bind, o.port, api, o.limits, access, tls);
    std::optional<fnet::web::HttpServer> dashboard;
    if (o.http_port) dashboard.emplace(io, o.bind, *o.http_port, api, o.limits, access, tls);
    context.connections = [&server, &dashboard] {
      return server.connections() + (dashboard ? dashboard->connections() : 0);
    };
    Ingest ingest(registry, {static_cast<dds_domainid_t>(o.domain), o.max_in_flight, o.max_in_flight_mib << 20,
                             o.max_frame_mib << 20});
    context.ingest_state = [&ingest] { return ingest.state(); };
    std::cout << "fnet-server listening on " << o.bind << ":" << server.port() << (tls ? " (TLS)" : "") << " data-dir "
              << o.data_dir << std::endl;
    if (dashboard)
      std::cout << "fnet-server dashboard on " << dashboard_address(o.bind, dashboard->port(), tls != nullptr)
                << std::endl;
    std::optional<StoreTending> tending(std::in_place, registry, ingest, server_name(o.data_dir));
    serve_until_signalled(io, server, dashboard);
    ingest.stop();
    tending.reset();
    stop_within(pool, registry, o.stop_timeout);  // finish what was taken, so the stores hold it
    std::cerr << "fnet-server: stopped\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "fnet-server: " << e.what() << "\n";
    return 1;
  }
}
