// What a JSON-RPC method of fnet-server is: the parameters it declares, what it runs, and what it
// gives back (at once, or as work for the analysis pool); and the context every method reads.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/registry/run_registry.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::server {

struct ApiContext {
  Registry& registry;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::size_t max_subscriptions_per_connection = 16;
  std::size_t max_heavy_calls_per_connection = 2;  // running at once; the next wait (heavy_calls.hpp)
  // A heavy call's computation past it is stopped (WorkDeadline) and answered with −32008.
  std::chrono::duration<double> max_call_seconds{60};
  std::function<std::size_t()> connections = [] { return std::size_t{0}; };
  // "running", or "stopped: <reason>" when the DDS ingest ended on an error.
  std::function<std::string()> ingest_state = [] { return std::string("not started"); };
  // Runs a heavy request's work (fnet-server: on the analysis pool, beside the frames' analysis,
  // so that the I/O threads stay free for every other client); by default at once.
  std::function<void(std::function<void()>)> offload = [](std::function<void()> work) { work(); };
};

// A heavy request's answer: the work that computes it, run through ApiContext::offload.
struct Deferred {
  std::function<nlohmann::json()> work;
};
// What a method gives back: its result at once, or the work that computes it.
using Reply = std::variant<nlohmann::json, Deferred>;
// A method whose every answer is heavy: it reads its params on the pool too.
template <class Fn>
auto heavy(Fn fn) {
  return [fn](const nlohmann::json& params, const std::shared_ptr<rpc::Peer>& peer) -> Reply {
    return Deferred{[fn, params, peer] { return fn(params, peer); }};
  };
}

// One method: every parameter it accepts (any other is an error, before it runs) and what it does.
struct Method {
  std::vector<std::string_view> params;
  std::function<Reply(const nlohmann::json& params, const std::shared_ptr<rpc::Peer>& session)> run;
};

using MethodTable = std::map<std::string, Method, std::less<>>;

}  // namespace fnet::server
