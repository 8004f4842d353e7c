// The JSON-RPC methods of fnet-server (proto/api.md is their reference).
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "server/analysis/rpc_server.hpp"
#include "server/analysis/run_registry.hpp"

namespace fnet::server {

struct ApiContext {
  Registry& registry;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::size_t max_subscriptions_per_connection = 16;
  std::function<std::size_t()> connections = [] { return std::size_t{0}; };
  // "running", or "stopped: <reason>" when the DDS ingest ended on an error.
  std::function<std::string()> ingest_state = [] { return std::string("not started"); };
};

rpc::Handler make_api(ApiContext& context);

}  // namespace fnet::server
