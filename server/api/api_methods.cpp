#include "server/api/api_methods.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "common/analysis/frame_analysis.hpp"
#include "common/analysis/metric_vocabulary.hpp"
#include "common/build_info/build_info.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/distance_json.hpp"
#include "common/codec/explain_json.hpp"
#include "common/codec/run_info_json.hpp"
#include "common/distance/work_deadline.hpp"
#include "common/store/analysis_store.hpp"
#include "server/api/api_params.hpp"
#include "server/api/block_methods.hpp"
#include "server/api/connection_subscriptions.hpp"
#include "server/api/ensemble_methods.hpp"
#include "server/api/heavy_calls.hpp"
#include "server/api/network_methods.hpp"
#include "server/api/registry_frames.hpp"
#include "server/api/series_methods.hpp"
#include "server/api/served_query.hpp"
#include "server/query/diagram_query.hpp"
#include "server/query/pair_query.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;
using rpc::Error;

constexpr std::uint32_t kMaxExplainTerms = 1000;

// ---- runs ------------------------------------------------------------------------------------

json summary_json(const RunSummary& s) {
  json out = {{"run", s.run_id},
              {"frames", s.frames},
              {"rejected", s.rejected},
              {"pending", s.pending},
              {"duplicates", s.duplicates},
              {"skipped", s.skipped},
              {"unstored", s.unstored},
              {"store_fault", s.store_fault.empty() ? json(nullptr) : json(s.store_fault)},
              {"first_frame", nullptr},
              {"last_frame", nullptr},
              {"rho", nullptr},
              {"z", nullptr},
              {"dimension", nullptr},
              {"rho_j", s.rho_j ? json(*s.rho_j) : json(nullptr)},
              {"seconds_since_last_frame", s.seconds_since_last_frame},
              {"last_activity", s.last_activity ? json(*s.last_activity) : json(nullptr)},
              {"announced", s.has_info}};
  if (s.last_frame) {
    out["first_frame"] = *s.first_frame;
    out["last_frame"] = *s.last_frame;
    out["rho"] = s.last_rho;
    out["z"] = s.last_z;
    out["dimension"] = s.dimension;
  }
  if (s.has_info) out["planned_frames"] = s.info.frames;
  return out;
}

json point_json(const SeriesPoint& p) {
  json distances = json::object();
  for (std::size_t k = 0; k < kStoredSeries.size(); ++k)
    distances[series_key(kStoredSeries[k])] = p.previous ? json(p.distances.value[k]) : json(nullptr);
  return {{"run", p.run_id},
          {"frame", p.header.index},
          {"step", p.header.step},
          {"time", p.header.time},
          {"rho", p.header.rho},
          {"z", p.header.z},
          {"previous", p.previous ? json(*p.previous) : json(nullptr)},
          {"distances", distances}};
}

// ---- methods -----------------------------------------------------------------------------------
// Each checks every parameter before it looks the run up, so a malformed request is reported as such.

json runs_list(const Registry& registry) {
  json runs = json::array();
  for (const RunSummary& s : registry.runs()) runs.push_back(summary_json(s));
  return {{"runs", runs}};
}

json run_get(const Registry& registry, const json& params) {
  const std::string run = resolve_run(registry, params);
  const auto s = registry.run(run);
  if (!s) unknown_run(run);
  json out = summary_json(*s);
  out["parameters"] = s->has_info ? to_json(s->info) : json(nullptr);
  json rejected = json::array();
  for (const RejectedFrame& r : registry.rejected(run)) rejected.push_back({{"frame", r.index}, {"reason", r.reason}});
  out["rejected_frames"] = rejected;
  return out;
}

// diagram.get: params -> DiagramRequest -> diagram_query -> JSON.
json diagram_get(const Registry& registry, const json& params) {
  query::DiagramRequest r;
  r.frame = require_index(params, "frame");
  r.dim = get_dim(params);
  r.force = get_force(params);
  r.run = resolve_run(registry, params);
  const query::DiagramAnswer d = served([&] { return query::diagram_query(RegistryFrames(registry), r); });
  return {{"run", r.run},
          {"frame", r.frame},
          {"dim", r.dim},
          {"force", to_string(r.force)},
          {"rho", d.header.rho},
          {"z", d.header.z},
          {"vertices", d.vertices},
          {"edges", d.edges},
          {"triangles", d.triangles},
          {"points", to_json(d.points)}};
}

// distance.get's parameters, each checked before any run is looked up.
query::PairRequest get_pair_request(const Registry& registry, const json& params) {
  query::PairRequest r;
  r.frame = require_index(params, "frame");
  r.other_frame = require_index(params, "other_frame");
  r.measure = get_step_query(params);
  r.delta = get_number(params, "delta").value_or(0);
  if (!(r.delta >= 0)) invalid("delta", "parameter 'delta' must be >= 0 (0: exact)");
  const auto explain_terms = get_index(params, "explain");
  if (explain_terms && (*explain_terms < 1 || *explain_terms > kMaxExplainTerms))
    invalid("explain", "parameter 'explain' must be an integer from 1 to " + std::to_string(kMaxExplainTerms) +
                           " (the number of terms), got " + std::to_string(*explain_terms));
  if (explain_terms) r.explain_terms = *explain_terms;
  r.run = resolve_run(registry, params, "run");
  r.other_run = find(params, "other_run") ? resolve_run(registry, params, "other_run") : r.run;
  return r;
}

// distance.get: params -> PairRequest -> pair_query -> JSON.
json distance_get(const Registry& registry, const json& params) {
  const query::PairRequest r = get_pair_request(registry, params);
  const query::PairAnswer a = served([&] { return query::pair_query(RegistryFrames(registry), r); });
  json out = to_json(a.distance);
  out.update(describe(r.measure));
  out["run"] = r.run;
  out["frame"] = r.frame;
  out["other_run"] = r.other_run;
  out["other_frame"] = r.other_frame;
  if (a.explained) out["explain"] = explain_terms_json(*a.explained);
  out["seconds"] = a.seconds;
  return out;
}

json server_status(const ApiContext& ctx) {
  const Registry& r = ctx.registry;
  const Counters c = r.counters();
  json rejections = json::array();
  for (const std::string& s : r.recent_rejections()) rejections.push_back(s);
  json runs = json::array(), faults = json::array();
  for (const RunSummary& s : r.runs()) {
    runs.push_back(summary_json(s));
    if (!s.store_fault.empty())
      faults.push_back({{"run", s.run_id}, {"reason", s.store_fault}, {"unstored", s.unstored}});
  }
  const BuildInfo b = build_info();
  const FrameCacheStats cache = r.cache_stats();
  return {{"uptime_seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - ctx.started).count()},
          {"build",
           {{"version", b.version},
            {"commit", b.commit},
            {"store_schema", kStoreSchema},
            {"convention", kStoreConvention},
            {"api", "json-rpc-2.0 (proto/api.md)"}}},
          {"ingest", ctx.ingest_state()},
          {"runs", runs},
          {"stores", {{"open", r.stores_open()}, {"faults", faults}}},
          {"cache",
           {{"capacity_bytes", cache.capacity_bytes},
            {"bytes", cache.bytes},
            {"entries", cache.entries},
            {"hits", cache.hits},
            {"misses", cache.misses}}},
          {"frames_per_second", r.frames_per_second()},
          {"lag", {{"frames_in_flight", r.in_flight()}, {"oldest_pending_seconds", r.oldest_pending_seconds()}}},
          {"frames",
           {{"received", c.received},
            {"analyzed", c.analyzed},
            {"rejected", c.rejected},
            {"duplicates", c.duplicates},
            {"late", c.late},
            {"skipped", c.skipped},
            {"malformed", c.malformed}}},
          {"rejections", rejections},
          {"refused_stores", r.refused_stores()},
          {"connections", ctx.connections()},
          {"subscriptions", r.subscriptions()}};
}

// ---- subscriptions: each connection's, released when it closes --------------------------------

// A series subscription as its client receives it, whatever the transport: each point a
// series.point notification, built off the registry's lock.
class PeerSeries final : public Subscriber {
 public:
  explicit PeerSeries(std::weak_ptr<rpc::Peer> peer) : peer_(std::move(peer)) {}
  bool deliver(std::uint64_t subscription, const SeriesPoint& p) override {
    const auto peer = peer_.lock();
    if (!peer) return false;
    json params = point_json(p);
    params["subscription"] = subscription;
    return peer->send(rpc::notification("series.point", std::move(params)));
  }
  bool ready(const std::function<void()>& resume) override {
    const auto peer = peer_.lock();
    return !peer || peer->wait_for_room(resume);  // a closed peer: deliver() ends the subscription
  }

 private:
  const std::weak_ptr<rpc::Peer> peer_;
};

class Subscriptions {
 public:
  explicit Subscriptions(ApiContext& ctx)
      : ctx_(ctx),
        held_(std::make_shared<ConnectionSubscriptions>(ctx.registry, ctx.max_subscriptions_per_connection,
                                                        "subscription")) {}

  json subscribe(const json& params, const std::shared_ptr<rpc::Peer>& session) {
    const auto since = get_index(params, "since");
    const std::string run = get_string(params, "run").value_or("");
    Registry& registry = ctx_.registry;
    if (!run.empty() && !registry.has_run(run)) unknown_run(registry, run);
    held_->check_room(*session);
    const std::uint64_t id = registry.subscribe(run, since, std::make_shared<PeerSeries>(session));
    held_->add(session, id);
    return {{"subscription", id}, {"run", run.empty() ? json(nullptr) : json(run)}};
  }

  json unsubscribe(const json& params, const std::shared_ptr<rpc::Peer>& session) {
    const std::uint32_t id = require_index(params, "subscription");
    held_->remove(*session, id);
    return {{"unsubscribed", id}};
  }

 private:
  ApiContext& ctx_;
  const std::shared_ptr<ConnectionSubscriptions> held_;
};

// The params as an object, every name one the method accepts: a typo ("dimension") is an error,
// not a silently applied default.
json checked_params(const std::string& method, const Method& m, const json& params) {
  if (params.is_array()) {
    if (!params.empty())
      throw Error(rpc::kInvalidParams, "params of '" + method + "' must be an object of named parameters");
    return json::object();
  }
  for (const auto& [name, value] : params.items()) {
    if (std::find(m.params.begin(), m.params.end(), name) != m.params.end()) continue;
    json accepted = json::array();
    std::string list;
    for (const std::string_view p : m.params) {
      accepted.push_back(p);
      list += (list.empty() ? "" : ", ") + std::string(p);
    }
    throw Error(rpc::kInvalidParams,
                "unknown parameter '" + name + "' for method '" + method + "' (" +
                    (list.empty() ? std::string("it takes none") : "accepted: " + list) + ")",
                {{"parameter", name}, {"accepted", accepted}});
  }
  return params;
}

}  // namespace

// ---- the method table: what each method accepts drives the unknown-parameter check -------------

MethodTable method_table(ApiContext& ctx) {
  Registry& registry = ctx.registry;
  const auto subscriptions = std::make_shared<Subscriptions>(ctx);
  // distance.get and blocks.get compute (and may read two networks back from the store), network.get
  // reads one: heavy.
  const auto plain = [](auto fn) {
    return [fn](const json& params, const std::shared_ptr<rpc::Peer>&) { return fn(params); };
  };
  MethodTable table{
      {"runs.list", {{}, plain([&registry](const json&) { return runs_list(registry); })}},
      {"run.get", {{"run"}, plain([&registry](const json& p) { return run_get(registry, p); })}},
      {"series.get", series_get_method(registry)},
      {"diagram.get",
       {{"frame", "run", "dim", "force"}, plain([&registry](const json& p) { return diagram_get(registry, p); })}},
      {"distance.get",
       {{"frame", "other_frame", "metric", "q", "run", "other_run", "dim", "force", "essential", "delta", "explain"},
        heavy(plain([&registry](const json& p) { return distance_get(registry, p); }))}},
      {"network.get",
       {{"frame", "run"}, heavy(plain([&registry](const json& p) { return network_get(registry, p); }))}},
      {"blocks.get",
       {{"run", "frame", "other_frame", "k", "metric", "q", "dim", "force", "essential"},
        heavy(plain([&registry](const json& p) { return blocks_get(registry, p); }))}},
      {"series.subscribe",
       {{"run", "since"},
        [subscriptions](const json& p, const std::shared_ptr<rpc::Peer>& s) {
          return subscriptions->subscribe(p, s);
        }}},
      {"series.unsubscribe",
       {{"subscription"},
        [subscriptions](const json& p, const std::shared_ptr<rpc::Peer>& s) {
          return subscriptions->unsubscribe(p, s);
        }}},
      {"server.status", {{}, plain([&ctx](const json&) { return server_status(ctx); })}},
      {"server.rescan", {{}, plain([&registry](const json&) {
                           const Registry::Adopted a = registry.adopt_new_stores();
                           return json{{"adopted", a.runs}, {"problems", a.problems}};
                         })}},
  };
  table.merge(ensemble_methods(ctx));
  return table;
}

rpc::Handler make_api(ApiContext& ctx) {
  auto table = std::make_shared<const MethodTable>(method_table(ctx));
  const auto heavy_calls = std::make_shared<HeavyCalls>(
      [&ctx](std::function<void()> work) { ctx.offload(std::move(work)); }, ctx.max_heavy_calls_per_connection);
  const std::chrono::duration<double> budget = ctx.max_call_seconds;
  return [table, heavy_calls, budget](const std::string& method, const json& params,
                                      const std::shared_ptr<rpc::Peer>& session, rpc::Completion done) {
    const auto it = table->find(method);
    if (it == table->end()) throw Error(rpc::kMethodNotFound, "unknown method '" + method + "'");
    const Method& m = it->second;
    const json checked = checked_params(method, m, params);
    Reply reply = [&] {
      const ReadingParams reading(m.params);
      return m.run(checked, session);
    }();
    if (json* result = std::get_if<json>(&reply)) return done(std::move(*result), nullptr);
    heavy_calls->submit(session ? session->id() : 0, [work = std::move(std::get<Deferred>(reply).work),
                                                      declared = &m.params, done, table, budget] {
      try {
        const ReadingParams reading(*declared);
        const WorkDeadline deadline(budget);
        done(work(), nullptr);
      } catch (const WorkDeadlineExceeded& e) {
        done(nullptr, std::make_exception_ptr(Error(rpc::kLimitExceeded, std::string("call stopped: ") + e.what(),
                                                    {{"limit", "max_call_seconds"}, {"value", e.seconds()}})));
      } catch (...) {
        done(nullptr, std::current_exception());
      }
    });
  };
}

}  // namespace fnet::server
