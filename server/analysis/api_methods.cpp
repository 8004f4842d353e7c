#include "server/analysis/api_methods.hpp"

#include <cmath>
#include <memory>
#include <mutex>
#include <set>

#include "common/analysis/frame_analysis.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/distance_json.hpp"
#include "common/codec/run_info_json.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;
using rpc::Error;

// ---- parameter parsing: every failure names the parameter -----------------------------------

const json* find(const json& params, const char* name) {
  if (!params.is_object()) throw Error(rpc::kInvalidParams, "params must be an object");
  const auto it = params.find(name);
  return it == params.end() || it->is_null() ? nullptr : &*it;
}

std::string get_string(const json& params, const char* name, std::optional<std::string> fallback = std::nullopt) {
  const json* v = find(params, name);
  if (!v) {
    if (fallback) return *fallback;
    throw Error(rpc::kInvalidParams, std::string("missing parameter '") + name + "'");
  }
  if (!v->is_string()) throw Error(rpc::kInvalidParams, std::string("parameter '") + name + "' must be a string");
  return v->get<std::string>();
}

std::optional<std::uint32_t> get_index(const json& params, const char* name) {
  const json* v = find(params, name);
  if (!v) return std::nullopt;
  if (!v->is_number_integer() || v->get<std::int64_t>() < 0 || v->get<std::int64_t>() > UINT32_MAX)
    throw Error(rpc::kInvalidParams, std::string("parameter '") + name + "' must be a non-negative integer");
  return static_cast<std::uint32_t>(v->get<std::int64_t>());
}

std::uint32_t require_index(const json& params, const char* name) {
  const auto v = get_index(params, name);
  if (!v) throw Error(rpc::kInvalidParams, std::string("missing parameter '") + name + "'");
  return *v;
}

double get_number(const json& params, const char* name, double fallback) {
  const json* v = find(params, name);
  if (!v) return fallback;
  if (!v->is_number() || !std::isfinite(v->get<double>()))
    throw Error(rpc::kInvalidParams, std::string("parameter '") + name + "' must be a finite number");
  return v->get<double>();
}

int get_dim(const json& params) {
  const json* v = find(params, "dim");
  if (!v) return 0;
  if (!v->is_number_integer() || (v->get<int>() != 0 && v->get<int>() != 1))
    throw Error(rpc::kInvalidParams, "parameter 'dim' must be 0 or 1");
  return v->get<int>();
}

ForceKind get_force(const json& params) {
  try {
    return parse_force_kind(get_string(params, "force", "normal"));
  } catch (const std::invalid_argument& e) {
    throw Error(rpc::kInvalidParams, std::string("parameter 'force': ") + e.what());
  }
}

EssentialConvention get_essential(const json& params) {
  try {
    return parse_essential_convention(get_string(params, "essential", "floor"));
  } catch (const std::invalid_argument& e) {
    throw Error(rpc::kInvalidParams, std::string("parameter 'essential': ") + e.what());
  }
}

// A metric request: bottleneck | wasserstein1 | wasserstein2 | wasserstein (with q >= 1).
struct MetricSpec {
  std::string name;
  double q = 0;                  // 0 for bottleneck
  std::optional<Metric> stored;  // one of the three metrics every frame carries
  DistanceMetric distance;
};

MetricSpec get_metric(const json& params) {
  MetricSpec m;
  m.name = get_string(params, "metric");
  if (m.name == "bottleneck")
    m.stored = Metric::bottleneck;
  else if (m.name == "wasserstein1")
    m.stored = Metric::wasserstein1, m.q = 1;
  else if (m.name == "wasserstein2")
    m.stored = Metric::wasserstein2, m.q = 2;
  else if (m.name == "wasserstein") {
    m.q = get_number(params, "q", 0);
    if (!(m.q >= 1)) throw Error(rpc::kInvalidParams, "metric 'wasserstein' needs parameter 'q' >= 1");
    if (m.q == 1) m.stored = Metric::wasserstein1;
    if (m.q == 2) m.stored = Metric::wasserstein2;
  } else {
    throw Error(rpc::kInvalidParams,
                "unknown metric '" + m.name + "' (expected bottleneck, wasserstein1, wasserstein2 or wasserstein)");
  }
  if (m.name != "bottleneck") m.distance = DistanceMetric::wasserstein(m.q);
  return m;
}

json describe(const MetricSpec& m, int dim, ForceKind force, EssentialConvention essential) {
  json out = {{"metric", m.name}, {"dim", dim}, {"force", to_string(force)}, {"essential", to_string(essential)}};
  if (m.q > 0) out["q"] = m.q;
  return out;
}

// ---- runs ------------------------------------------------------------------------------------

std::string resolve_run(const Registry& registry, const json& params, const char* name = "run") {
  std::string run = get_string(params, name, std::string());
  if (run.empty()) {
    run = registry.newest_run();
    if (run.empty()) throw Error(rpc::kUnknownRun, "the server has no runs yet");
    return run;
  }
  if (!registry.has_run(run)) throw Error(rpc::kUnknownRun, "unknown run '" + run + "'", {{"run", run}});
  return run;
}

json summary_json(const RunSummary& s) {
  json out = {{"run", s.run_id},
              {"frames", s.frames},
              {"rejected", s.rejected},
              {"pending", s.pending},
              {"duplicates", s.duplicates},
              {"skipped", s.skipped},
              {"first_frame", nullptr},
              {"last_frame", nullptr},
              {"rho", nullptr},
              {"z", nullptr},
              {"seconds_since_last_frame", s.seconds_since_last_frame},
              {"announced", s.has_info}};
  if (s.last_frame) {
    out["first_frame"] = *s.first_frame;
    out["last_frame"] = *s.last_frame;
    out["rho"] = s.last_rho;
    out["z"] = s.last_z;
  }
  if (s.has_info) out["planned_frames"] = s.info.frames;
  return out;
}

json point_json(const SeriesPoint& p) {
  json distances = json::object();
  for (const Metric metric : kMetrics)
    for (int dim = 0; dim < 2; ++dim)
      for (const ForceKind force : kForces) {
        const std::string key =
            std::string(to_string(metric)) + "/pd" + std::to_string(dim) + "/" + std::string(to_string(force));
        distances[key] = p.previous ? json(p.distances(metric, dim, force)) : json(nullptr);
      }
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

json series_get(const Registry& registry, const json& params) {
  // Every parameter is checked before the run is looked up, so a malformed request is reported as such.
  const MetricSpec metric = get_metric(params);
  const int dim = get_dim(params);
  const ForceKind force = get_force(params);
  const EssentialConvention essential = get_essential(params);
  const auto from = get_index(params, "from"), to = get_index(params, "to");
  const std::string run = resolve_run(registry, params);
  const auto frames = registry.frames(run);
  if (!frames) throw Error(rpc::kUnknownRun, "unknown run '" + run + "'");

  json out = describe(metric, dim, force, essential);
  out["run"] = run;
  json frame = json::array(), rho = json::array(), z = json::array(), value = json::array(), previous = json::array();
  json infinite = json::array();
  bool any_infinite = false;
  std::shared_ptr<const AnalyzedFrame> before;  // the frame committed before the current one
  for (const auto& f : *frames) {
    const std::uint32_t index = f->header.index;
    const auto prev_frame = before;
    before = f;
    if ((from && index < *from) || (to && index > *to)) continue;
    frame.push_back(index);
    rho.push_back(f->header.rho);
    z.push_back(f->header.z);
    previous.push_back(f->previous ? json(*f->previous) : json(nullptr));
    if (!f->previous || !prev_frame) {
      value.push_back(nullptr);
      infinite.push_back(false);
      continue;
    }
    if (metric.stored && essential == EssentialConvention::floor) {
      value.push_back(f->distances(*metric.stored, dim, force));
      infinite.push_back(false);
      continue;
    }
    const DistanceResult r = diagram_distance(diagram_of(prev_frame->diagrams, force, dim),
                                              diagram_of(f->diagrams, force, dim), metric.distance, essential);
    value.push_back(r.infinite ? json(nullptr) : json(r.value));
    infinite.push_back(r.infinite);
    any_infinite |= r.infinite;
  }
  out["frame"] = frame;
  out["rho"] = rho;
  out["z"] = z;
  out["value"] = value;
  out["previous"] = previous;
  if (any_infinite) out["infinite"] = infinite;
  return out;
}

json diagram_get(const Registry& registry, const json& params) {
  const std::uint32_t index = require_index(params, "frame");
  const int dim = get_dim(params);
  const ForceKind force = get_force(params);
  const std::string run = resolve_run(registry, params);
  const auto f = registry.frame(run, index);
  if (!f)
    throw Error(rpc::kUnknownFrame, "run '" + run + "' has no analyzed frame " + std::to_string(index),
                {{"run", run}, {"frame", index}});
  const FrameDiagrams& d = f->diagrams[force];
  return {{"run", run},
          {"frame", index},
          {"dim", dim},
          {"force", to_string(force)},
          {"rho", f->header.rho},
          {"z", f->header.z},
          {"vertices", d.vertices},
          {"edges", d.edges},
          {"triangles", d.triangles},
          {"points", to_json(dim == 0 ? d.pd0 : d.pd1)}};
}

json distance_get(const Registry& registry, const json& params) {
  const std::uint32_t frame_a = require_index(params, "frame");
  const std::uint32_t frame_b = require_index(params, "other_frame");
  const MetricSpec metric = get_metric(params);
  const int dim = get_dim(params);
  const ForceKind force = get_force(params);
  const EssentialConvention essential = get_essential(params);
  const double delta = get_number(params, "delta", 0);
  if (delta < 0) throw Error(rpc::kInvalidParams, "parameter 'delta' must be >= 0");
  const std::string run_a = resolve_run(registry, params, "run");
  const std::string run_b = find(params, "other_run") ? resolve_run(registry, params, "other_run") : run_a;
  const auto a = registry.frame(run_a, frame_a), b = registry.frame(run_b, frame_b);
  if (!a) throw Error(rpc::kUnknownFrame, "run '" + run_a + "' has no analyzed frame " + std::to_string(frame_a));
  if (!b) throw Error(rpc::kUnknownFrame, "run '" + run_b + "' has no analyzed frame " + std::to_string(frame_b));
  const auto start = std::chrono::steady_clock::now();
  const DistanceResult r = diagram_distance(diagram_of(a->diagrams, force, dim), diagram_of(b->diagrams, force, dim),
                                            metric.distance, essential, delta);
  json out = to_json(r);
  out.update(describe(metric, dim, force, essential));
  out["run"] = run_a;
  out["frame"] = frame_a;
  out["other_run"] = run_b;
  out["other_frame"] = frame_b;
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

json server_status(const ApiContext& ctx) {
  const Registry& r = ctx.registry;
  const Counters c = r.counters();
  json rejections = json::array();
  for (const std::string& s : r.recent_rejections()) rejections.push_back(s);
  json runs = json::array();
  for (const RunSummary& s : r.runs()) runs.push_back(summary_json(s));
  return {{"uptime_seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - ctx.started).count()},
          {"runs", runs},
          {"frames_per_second", r.frames_per_second()},
          {"lag",
           {{"frames_in_flight", r.in_flight()},
            {"ingest_queue", ctx.ingest_queue()},
            {"oldest_pending_seconds", r.oldest_pending_seconds()}}},
          {"frames",
           {{"received", c.received},
            {"analyzed", c.analyzed},
            {"rejected", c.rejected},
            {"duplicates", c.duplicates},
            {"late", c.late},
            {"skipped", c.skipped},
            {"malformed", c.malformed}}},
          {"rejections", rejections},
          {"connections", ctx.connections()},
          {"subscriptions", r.subscriptions()}};
}

// Subscriptions of one connection, released when it closes.
struct SessionSubscriptions {
  std::mutex mutex;
  std::set<std::uint64_t> ids;
};

}  // namespace

rpc::Handler make_api(ApiContext& ctx) {
  // Per-session subscription sets, keyed by session id; entries go when the session closes.
  auto sessions = std::make_shared<std::map<std::uint64_t, std::shared_ptr<SessionSubscriptions>>>();
  auto sessions_mutex = std::make_shared<std::mutex>();

  return [&ctx, sessions, sessions_mutex](const std::string& method, const json& params,
                                          const std::shared_ptr<rpc::Session>& session) -> json {
    Registry& registry = ctx.registry;
    if (method == "runs.list") {
      json runs = json::array();
      for (const RunSummary& s : registry.runs()) runs.push_back(summary_json(s));
      return {{"runs", runs}};
    }
    if (method == "run.get") {
      const std::string run = resolve_run(registry, params);
      const auto s = registry.run(run);
      json out = summary_json(*s);
      out["parameters"] = s->has_info ? to_json(s->info) : json(nullptr);
      json rejected = json::array();
      for (const RejectedFrame& r : registry.rejected(run))
        rejected.push_back({{"frame", r.index}, {"reason", r.reason}});
      out["rejected_frames"] = rejected;
      return out;
    }
    if (method == "series.get") return series_get(registry, params);
    if (method == "diagram.get") return diagram_get(registry, params);
    if (method == "distance.get") return distance_get(registry, params);
    if (method == "server.status") return server_status(ctx);
    if (method == "series.subscribe") {
      const std::string run = get_string(params, "run", std::string());
      if (!run.empty() && !registry.has_run(run)) throw Error(rpc::kUnknownRun, "unknown run '" + run + "'");
      const auto since = get_index(params, "since");
      std::shared_ptr<SessionSubscriptions> mine;
      {
        std::lock_guard lock(*sessions_mutex);
        auto& slot = (*sessions)[session->id()];
        if (!slot) {
          slot = std::make_shared<SessionSubscriptions>();
          session->on_close([&registry, sessions, sessions_mutex, id = session->id()] {
            std::shared_ptr<SessionSubscriptions> subs;
            {
              std::lock_guard inner(*sessions_mutex);
              subs = (*sessions)[id];
              sessions->erase(id);
            }
            if (!subs) return;
            std::lock_guard inner(subs->mutex);
            for (const std::uint64_t s : subs->ids) registry.unsubscribe(s);
          });
        }
        mine = slot;
      }
      {
        std::lock_guard lock(mine->mutex);
        if (mine->ids.size() >= ctx.max_subscriptions_per_connection)
          throw Error(rpc::kTooManySubscriptions, "at most " + std::to_string(ctx.max_subscriptions_per_connection) +
                                                      " subscriptions per connection");
      }
      std::weak_ptr<rpc::Session> weak = session;
      const std::uint64_t id = registry.subscribe(run, since, [weak](std::uint64_t subscription, const SeriesPoint& p) {
        const auto s = weak.lock();
        if (!s) return false;
        json params_out = point_json(p);
        params_out["subscription"] = subscription;
        return s->send(rpc::notification("series.point", std::move(params_out)));
      });
      if (id == 0) throw Error(rpc::kInternalError, "connection closed while sending the backlog");
      std::lock_guard lock(mine->mutex);
      mine->ids.insert(id);
      return {{"subscription", id}, {"run", run.empty() ? json(nullptr) : json(run)}};
    }
    if (method == "series.unsubscribe") {
      const auto id = get_index(params, "subscription");
      if (!id) throw Error(rpc::kInvalidParams, "missing parameter 'subscription'");
      std::shared_ptr<SessionSubscriptions> mine;
      {
        std::lock_guard lock(*sessions_mutex);
        const auto it = sessions->find(session->id());
        if (it != sessions->end()) mine = it->second;
      }
      bool found = false;
      if (mine) {
        std::lock_guard lock(mine->mutex);
        found = mine->ids.erase(*id) > 0;
      }
      if (!found) throw Error(rpc::kInvalidParams, "no subscription " + std::to_string(*id) + " on this connection");
      registry.unsubscribe(*id);
      return {{"unsubscribed", *id}};
    }
    throw Error(rpc::kMethodNotFound, "unknown method '" + method + "'");
  };
}

}  // namespace fnet::server
