#include "server/api/ensemble_methods.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <set>

#include "common/analysis/ensemble_curve.hpp"
#include "common/analysis/step_series.hpp"
#include "server/api/api_params.hpp"
#include "server/api/connection_subscriptions.hpp"
#include "server/api/registry_frames.hpp"
#include "server/api/series_columns.hpp"
#include "server/query/curve_query.hpp"

namespace fnet::server {
namespace {

using json = nlohmann::json;
using rpc::Error;

constexpr double kDefaultBinWidth = 0.002;
// rho and rho - rho_J lie within [-1, 1]: a finer width would only make bins of one frame each,
// and the bin indices must stay far inside 64 bits.
constexpr double kMinBinWidth = 1e-9;
constexpr std::uint32_t kMaxBins = 1000000;

using query::Curve;
using query::CurveAxis;
using query::CurveRequest;
using query::StepCache;

[[noreturn]] void unknown_ensemble(const std::string& ensemble) {
  throw Error(rpc::kUnknownEnsemble, "unknown ensemble '" + ensemble + "': no announced run belongs to it",
              {{"ensemble", ensemble}});
}

// Every parameter checked before any run or ensemble is looked up.
CurveRequest get_curve_request(const Registry& registry, const json& params) {
  CurveRequest r;
  const auto ensemble = get_string(params, "ensemble"), run = get_string(params, "run");
  if (ensemble.has_value() == run.has_value())
    invalid("ensemble", ensemble ? "give 'ensemble' or 'run', not both"
                                 : "missing parameter 'ensemble' (or 'run', for one run's curve)");
  r.measure = get_series_measure(params);
  const auto width = get_number(params, "bin_width");
  const json* bins = find(params, "bins");
  if (width && bins) invalid("bin_width", "give 'bin_width' or 'bins', not both");
  if (bins) {
    if (!bins->is_number_integer()) wrong_type("bins", "an integer >= 1", *bins);
    const bool fits = bins->is_number_unsigned()
                          ? bins->get<std::uint64_t>() <= kMaxBins
                          : bins->get<std::int64_t>() >= 1 && bins->get<std::int64_t>() <= kMaxBins;
    if (!fits || bins->get<std::int64_t>() < 1)
      invalid("bins", "parameter 'bins' must be an integer from 1 to " + std::to_string(kMaxBins) + " (got " +
                          bins->dump() + ")");
    r.binning.count = bins->get<std::size_t>();
  } else {
    r.binning.width = width.value_or(kDefaultBinWidth);
    if (!(std::isfinite(r.binning.width) && r.binning.width >= kMinBinWidth))
      invalid("bin_width", "parameter 'bin_width' must be a finite number >= 1e-9 (a width in rho), got " +
                               json(r.binning.width).dump());
  }
  const std::string axis = get_string(params, "axis").value_or("rho");
  if (axis == "rho_minus_rho_j")
    r.axis = CurveAxis::rho_minus_rho_j;
  else if (axis != "rho")
    invalid("axis", "parameter 'axis' must be rho or rho_minus_rho_j, got '" + axis + "'");
  if (run) {
    if (run->empty() || !registry.has_run(*run)) unknown_run(registry, *run);
    r.run = *run;
  } else {
    if (registry.ensemble_members(*ensemble).empty()) unknown_ensemble(*ensemble);
    r.ensemble = *ensemble;
  }
  return r;
}

// The curve over the registry's runs as they are now (server/query/curve_query.hpp).
Curve compute_curve(const Registry& registry, const CurveRequest& r, StepCache& cache) {
  return query::compute_curve(RegistryFrames(registry), r, cache);
}

json strings(const std::vector<std::string>& v) {
  json out = json::array();
  for (const std::string& s : v) out.push_back(s);
  return out;
}

// The bins as equal-length arrays; a mean of +inf is null with infinite[k] true (the key present
// only when some is), a 0/0 ratio null.
void put_bins(json& out, const std::vector<CurveBin>& bins) {
  json lo = json::array(), hi = json::array(), rho = json::array(), mean = json::array(), se = json::array(),
       n_runs = json::array(), n = json::array(), z = json::array(), infinite = json::array();
  bool any_infinite = false;
  for (const CurveBin& b : bins) {
    lo.push_back(b.rho_lo);
    hi.push_back(b.rho_hi);
    rho.push_back(b.mean_rho);
    const bool inf = std::isinf(b.mean);
    any_infinite |= inf;
    mean.push_back(std::isfinite(b.mean) ? json(b.mean) : json(nullptr));
    infinite.push_back(inf);
    se.push_back(b.standard_error ? json(*b.standard_error) : json(nullptr));
    n_runs.push_back(b.runs);
    n.push_back(b.n);
    z.push_back(b.mean_z);
  }
  out["rho_lo"] = lo;
  out["rho_hi"] = hi;
  out["rho"] = rho;
  out["mean"] = mean;
  out["stderr"] = se;
  out["n_runs"] = n_runs;
  out["n"] = n;
  out["z"] = z;
  if (any_infinite) out["infinite"] = infinite;
}

// What every answer about a curve says it is, and the members it was computed over.
json curve_head(const CurveRequest& r, const Curve& c) {
  json out = describe(r.measure.query);
  out["ensemble"] = r.ensemble.empty() ? json(nullptr) : json(r.ensemble);
  out["run"] = r.run.empty() ? json(nullptr) : json(r.run);
  out["runs"] = strings(c.runs);
  out["axis"] = r.axis == CurveAxis::rho ? "rho" : "rho_minus_rho_j";
  out["ratio"] = r.measure.ratio.empty() ? json(nullptr) : json(r.measure.ratio);
  if (r.binning.count > 0)
    out["bins"] = r.binning.count;
  else
    out["bin_width"] = r.binning.width;
  if (r.axis == CurveAxis::rho_minus_rho_j) out["runs_without_rho_j"] = strings(c.runs_without_rho_j);
  if (!c.left_out.empty()) out["left_out"] = strings(c.left_out);
  return out;
}

json curve_json(const CurveRequest& r, const Curve& c) {
  json out = curve_head(r, c);
  put_bins(out, c.bins);
  return out;
}

json ensemble_series(const Registry& registry, const json& params) {
  const CurveRequest r = get_curve_request(registry, params);
  StepCache cache;
  return curve_json(r, compute_curve(registry, r, cache));
}

// ---- ensembles.list ---------------------------------------------------------------------------

json ensembles_list(const Registry& registry) {
  std::map<std::string, std::vector<RunSummary>> by_ensemble;
  for (RunSummary& s : registry.runs())
    if (s.has_info && !s.info.ensemble.empty()) by_ensemble[s.info.ensemble].push_back(std::move(s));
  json out = json::array();
  for (const auto& entry : by_ensemble) {
    // Named, not bound: clang before 16 cannot capture a structured binding in a lambda.
    const std::string& name = entry.first;
    const std::vector<RunSummary>& members = entry.second;
    std::size_t frames = 0;
    std::vector<double> rho_j;
    std::optional<StoreTime> last;
    for (const RunSummary& s : members) {
      frames += s.frames;
      if (s.rho_j) rho_j.push_back(*s.rho_j);
      if (s.last_activity && (!last || *s.last_activity > *last)) last = s.last_activity;
    }
    // The setting the members share; null where they differ (realizations of one setting should not).
    const auto shared = [&](auto field) {
      const auto first = field(members.front().info);
      for (const RunSummary& s : members)
        if (field(s.info) != first) return json(nullptr);
      return json(first);
    };
    json rj = {{"mean", nullptr}, {"standard_error", nullptr}, {"n", rho_j.size()}};
    if (!rho_j.empty()) {
      double sum = 0;
      for (const double v : rho_j) sum += v;
      const double n = static_cast<double>(rho_j.size()), mean = sum / n;
      rj["mean"] = mean;
      if (rho_j.size() >= 2) {
        double squares = 0;
        for (const double v : rho_j) squares += (v - mean) * (v - mean);
        rj["standard_error"] = std::sqrt(squares / (n - 1)) / std::sqrt(n);
      }
    }
    json runs = json::array();
    for (const RunSummary& s : members) runs.push_back(s.run_id);
    out.push_back({{"ensemble", name},
                   {"runs", runs},
                   {"frames", frames},
                   {"friction", shared([](const RunInfo& i) { return i.friction; })},
                   {"particles", shared([](const RunInfo& i) { return i.particles; })},
                   {"compression_speed", shared([](const RunInfo& i) { return i.compression_speed; })},
                   {"rho_j", rj},
                   {"last_activity", last ? json(*last) : json(nullptr)}});
  }
  return {{"ensembles", out}};
}

// ---- subscriptions ----------------------------------------------------------------------------

bool same_value(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

bool same_bin(const CurveBin& a, const CurveBin& b) {
  return same_value(a.rho_lo, b.rho_lo) && same_value(a.rho_hi, b.rho_hi) && same_value(a.mean_rho, b.mean_rho) &&
         same_value(a.mean, b.mean) && a.runs == b.runs && a.n == b.n && same_value(a.mean_z, b.mean_z) &&
         a.standard_error.has_value() == b.standard_error.has_value() &&
         (!a.standard_error || same_value(*a.standard_error, *b.standard_error));
}

class EnsembleSubscriptions;

// What an ensemble subscription asks of the registry: to be marked for recomputation when a
// member run commits a frame (the curve is recomputed on the analysis pool).
class MarkOnCommit final : public Subscriber {
 public:
  MarkOnCommit(std::weak_ptr<EnsembleSubscriptions> owner, std::string ensemble)
      : owner_(std::move(owner)), ensemble_(std::move(ensemble)) {}
  bool deliver(std::uint64_t subscription, const SeriesPoint& p) override;

 private:
  const std::weak_ptr<EnsembleSubscriptions> owner_;
  const std::string ensemble_;  // empty: a run's curve, marked by each of its points
};

// Recomputes a subscription's curve after each commit of a member run, off the registry's lock
// (a commit only marks the subscription; marks made before its recomputation starts count once),
// through ApiContext::offload (the analysis pool), and sends the bins that changed.
class EnsembleSubscriptions : public std::enable_shared_from_this<EnsembleSubscriptions> {
 public:
  // The connections' sets end a subscription through a weak pointer: they may outlive this.
  static std::shared_ptr<EnsembleSubscriptions> make(ApiContext& ctx) {
    auto self = std::make_shared<EnsembleSubscriptions>(ctx);
    self->held_ = std::make_shared<ConnectionSubscriptions>(
        ctx.registry, ctx.max_subscriptions_per_connection, "ensemble subscription",
        [weak = std::weak_ptr<EnsembleSubscriptions>(self)](std::uint64_t id) {
          if (const auto s = weak.lock()) s->forget(id);
        });
    // A realization announced after its last frame was committed (its announcement and its frames
    // travel on different topics) changes the curve although no commit follows.
    ctx.registry.on_announcement([weak = std::weak_ptr<EnsembleSubscriptions>(self)](const RunInfo& info) {
      if (const auto s = weak.lock()) s->mark_ensemble(info.ensemble);
    });
    return self;
  }
  explicit EnsembleSubscriptions(ApiContext& ctx) : ctx_(ctx) {}

  json subscribe(const json& params, const std::shared_ptr<rpc::Peer>& session) {
    Registry& registry = ctx_.registry;
    auto sub = std::make_shared<Subscription>();
    sub->request = get_curve_request(registry, params);
    sub->session = session;
    held_->check_room(*session);
    // Registered before the curve is first computed, and a recomputation waits for that computation
    // (the subscription's lock), so no commit falls between the reply and the first notification.
    std::unique_lock sub_lock(sub->mutex);
    std::weak_ptr<EnsembleSubscriptions> weak_self = weak_from_this();
    const std::string ensemble = sub->request.ensemble;
    const std::uint64_t id = registry.subscribe(sub->request.run, std::numeric_limits<std::uint32_t>::max(),
                                                std::make_shared<MarkOnCommit>(weak_self, ensemble));
    sub->id = id;
    {
      std::lock_guard lock(mutex_);
      subscriptions_[id] = sub;
    }
    held_->add(session, id);
    Curve c;
    try {
      c = compute_curve(registry, sub->request, sub->cache);
    } catch (...) {
      sub_lock.unlock();
      held_->drop(*session, id);
      throw;
    }
    sub->sent = c.bins;
    json out = curve_json(sub->request, c);
    out["subscription"] = id;
    return out;
  }

  json unsubscribe(const json& params, const std::shared_ptr<rpc::Peer>& session) {
    const std::uint32_t id = require_index(params, "subscription");
    held_->remove(*session, id);
    return {{"unsubscribed", id}};
  }

 private:
  friend class MarkOnCommit;  // marks a subscription when its runs commit
  struct Subscription {
    std::mutex mutex;  // held while its curve is computed and sent
    std::uint64_t id = 0;
    CurveRequest request;
    std::weak_ptr<rpc::Peer> session;
    StepCache cache;
    std::vector<CurveBin> sent;  // the bins as the subscriber has them
  };

  void forget(std::uint64_t id) {
    std::lock_guard lock(mutex_);
    subscriptions_.erase(id);
  }

  // Marks every subscription to `ensemble`'s curve (a run announced as its member).
  void mark_ensemble(const std::string& ensemble) {
    if (ensemble.empty()) return;
    std::vector<std::uint64_t> ids;
    {
      std::lock_guard lock(mutex_);
      for (const auto& [id, sub] : subscriptions_)
        if (sub->request.ensemble == ensemble) ids.push_back(id);
    }
    for (const std::uint64_t id : ids) mark(id);
  }

  // Schedules the subscription's recomputation, once until it starts.
  void mark(std::uint64_t id) {
    {
      std::lock_guard lock(mutex_);
      if (!scheduled_.insert(id).second) return;
    }
    ctx_.offload([weak = weak_from_this(), id] {
      if (const auto self = weak.lock()) self->recompute(id);
    });
  }

  void recompute(std::uint64_t id) {
    std::shared_ptr<Subscription> sub;
    {
      std::lock_guard lock(mutex_);
      scheduled_.erase(id);
      const auto it = subscriptions_.find(id);
      if (it == subscriptions_.end()) return;
      sub = it->second;
    }
    try {
      update(*sub);
    } catch (const std::exception&) {
      // A curve that cannot be computed now (a member's diagrams unusable) is retried at the next commit.
    }
  }

  void update(Subscription& sub) {
    std::lock_guard lock(sub.mutex);
    const auto session = sub.session.lock();
    if (!session) return;
    const Curve c = compute_curve(ctx_.registry, sub.request, sub.cache);
    std::vector<CurveBin> changed;
    for (const CurveBin& b : c.bins) {
      const auto old = std::find_if(sub.sent.begin(), sub.sent.end(),
                                    [&](const CurveBin& s) { return same_value(s.rho_lo, b.rho_lo); });
      if (old == sub.sent.end() || !same_bin(*old, b)) changed.push_back(b);
    }
    json removed = json::array();
    for (const CurveBin& s : sub.sent)
      if (std::none_of(c.bins.begin(), c.bins.end(), [&](const CurveBin& b) { return same_value(s.rho_lo, b.rho_lo); }))
        removed.push_back(s.rho_lo);
    if (changed.empty() && removed.empty()) return;
    json params = curve_head(sub.request, c);
    put_bins(params, changed);
    if (!removed.empty()) params["removed"] = removed;
    params["subscription"] = sub.id;
    sub.sent = c.bins;
    session->send(rpc::notification("ensemble.bins", std::move(params)));
  }

  ApiContext& ctx_;
  std::shared_ptr<ConnectionSubscriptions> held_;
  std::mutex mutex_;  // guards what follows
  std::map<std::uint64_t, std::shared_ptr<Subscription>> subscriptions_;
  std::set<std::uint64_t> scheduled_;  // recomputations posted and not yet started
};

bool MarkOnCommit::deliver(std::uint64_t subscription, const SeriesPoint& p) {
  const auto owner = owner_.lock();
  if (!owner) return false;
  if (ensemble_.empty() || p.ensemble == ensemble_) owner->mark(subscription);
  return true;
}

}  // namespace

MethodTable ensemble_methods(ApiContext& ctx) {
  Registry& registry = ctx.registry;
  const auto subscriptions = EnsembleSubscriptions::make(ctx);
  const std::vector<std::string_view> curve_params{"ensemble",  "run",       "metric", "q",    "dim",  "force",
                                                   "essential", "bin_width", "bins",   "axis", "ratio"};
  return {
      {"ensembles.list",
       {{}, [&registry](const json&, const std::shared_ptr<rpc::Peer>&) { return ensembles_list(registry); }}},
      // A curve bins every frame of every member run, computed from the diagrams for a metric
      // that is not stored: heavy.
      {"ensemble.series", {curve_params, heavy([&registry](const json& p, const std::shared_ptr<rpc::Peer>&) {
                             return ensemble_series(registry, p);
                           })}},
      {"ensemble.subscribe", {curve_params, heavy([subscriptions](const json& p, const std::shared_ptr<rpc::Peer>& s) {
                                return subscriptions->subscribe(p, s);
                              })}},
      {"ensemble.unsubscribe",
       {{"subscription"},
        [subscriptions](const json& p, const std::shared_ptr<rpc::Peer>& s) {
          return subscriptions->unsubscribe(p, s);
        }}},
  };
}

}  // namespace fnet::server
