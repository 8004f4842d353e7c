#include "server/api/api_params.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/run/run_names.hpp"
#include "server/api/close_names.hpp"

namespace fnet::server {

using rpc::Error;

// ---- parameter parsing: every failure names the parameter and what it must be ----------------

[[noreturn]] void invalid(std::string_view name, const std::string& message) {
  throw Error(rpc::kInvalidParams, message, {{"parameter", name}});
}

[[noreturn]] void wrong_type(std::string_view name, const char* expected, const json& got) {
  invalid(name, "parameter '" + std::string(name) + "' must be " + expected + " (got " + got.type_name() + ")");
}

// A parameter given as null is taken as omitted.
namespace {

// The parameters the method running on this thread declared (none outside a method: tests).
thread_local std::span<const std::string_view> t_declared;
thread_local bool t_in_method = false;

}  // namespace

ReadingParams::ReadingParams(std::span<const std::string_view> declared)
    : outer_(t_declared), outer_in_method_(t_in_method) {
  t_declared = declared;
  t_in_method = true;
}

ReadingParams::~ReadingParams() {
  t_declared = outer_;
  t_in_method = outer_in_method_;
}

const json* find(const json& params, std::string_view name) {
  if (t_in_method && std::find(t_declared.begin(), t_declared.end(), name) == t_declared.end())
    throw std::logic_error("a method read parameter '" + std::string(name) + "', which it does not declare");
  const auto it = params.find(name);
  return it == params.end() || it->is_null() ? nullptr : &*it;
}

std::optional<std::string> get_string(const json& params, std::string_view name) {
  const json* v = find(params, name);
  if (!v) return std::nullopt;
  if (!v->is_string()) wrong_type(name, "a string", *v);
  return v->get<std::string>();
}

std::optional<std::uint32_t> get_index(const json& params, std::string_view name) {
  const json* v = find(params, name);
  if (!v) return std::nullopt;
  // A negative number is number_integer, a large one number_unsigned: both are read without wrapping.
  const bool fits = v->is_number_unsigned() ? v->get<std::uint64_t>() <= UINT32_MAX
                                            : v->is_number_integer() && v->get<std::int64_t>() >= 0 &&
                                                  v->get<std::int64_t>() <= static_cast<std::int64_t>(UINT32_MAX);
  if (!fits) {
    if (!v->is_number_integer()) wrong_type(name, "a non-negative integer", *v);
    invalid(name,
            "parameter '" + std::string(name) + "' must be a non-negative integer below 2^32 (got " + v->dump() + ")");
  }
  return static_cast<std::uint32_t>(v->get<std::uint64_t>());
}

std::uint32_t require_index(const json& params, std::string_view name) {
  const auto v = get_index(params, name);
  if (!v) invalid(name, "missing parameter '" + std::string(name) + "'");
  return *v;
}

std::optional<double> get_number(const json& params, std::string_view name) {
  const json* v = find(params, name);
  if (!v) return std::nullopt;
  if (!v->is_number()) wrong_type(name, "a number", *v);
  return v->get<double>();
}

int get_dim(const json& params) {
  const json* v = find(params, "dim");
  if (!v) return kDefaultDim;
  if (!v->is_number_integer()) wrong_type("dim", "an integer, 0 or 1", *v);
  // Read as the widest integer: 2^32 once read as an int was dim 0.
  const long long dim = v->is_number_unsigned() && v->get<std::uint64_t>() > std::numeric_limits<long long>::max()
                            ? std::numeric_limits<long long>::max()
                            : v->get<long long>();
  try {
    return check_dim(dim);
  } catch (const std::invalid_argument& e) {
    invalid("dim", std::string("parameter 'dim': ") + e.what());
  }
}

ForceKind get_force(const json& params) {
  try {
    return parse_force_kind(get_string(params, "force").value_or("normal"));
  } catch (const std::invalid_argument& e) {
    invalid("force", std::string("parameter 'force': ") + e.what());
  }
}

EssentialConvention get_essential(const json& params) {
  try {
    return parse_essential_convention(get_string(params, "essential").value_or("floor"));
  } catch (const std::invalid_argument& e) {
    invalid("essential", std::string("parameter 'essential': ") + e.what());
  }
}

MetricChoice get_metric(const json& params) {
  const auto name = get_string(params, "metric");
  if (!name) invalid("metric", "missing parameter 'metric'");
  const auto q = get_number(params, "q");
  try {
    return parse_metric(*name, q);
  } catch (const std::invalid_argument& e) {
    // Name 'q' when it is the value at fault, 'metric' otherwise (an unknown name, or one that needs q).
    const bool names_q = q && std::find(kMetricNames.begin(), kMetricNames.end(), *name) != kMetricNames.end();
    invalid(names_q ? "q" : "metric", std::string("parameter '") + (names_q ? "q" : "metric") + "': " + e.what());
  }
}

json describe(const MetricChoice& m, int dim, ForceKind force, EssentialConvention essential) {
  json out = {{"metric", m.name}, {"dim", dim}, {"force", to_string(force)}, {"essential", to_string(essential)}};
  if (m.q) out["q"] = *m.q;
  return out;
}

namespace {

// dim, force and essential, after the metric.
StepQuery with_selection(const json& params, MetricChoice metric) {
  return {std::move(metric), get_dim(params), get_force(params), get_essential(params)};
}

}  // namespace

StepQuery get_step_query(const json& params) { return with_selection(params, get_metric(params)); }

SeriesMeasure get_series_measure(const json& params) {
  SeriesMeasure m;
  const auto ratio = get_string(params, "ratio");
  if (!ratio) {
    m.query = get_step_query(params);
    return m;
  }
  if (*ratio != "wasserstein1" && *ratio != "wasserstein2")
    invalid("ratio",
            "parameter 'ratio' must be wasserstein1 or wasserstein2 (the ratio d_B / d_Wq), got '" + *ratio + "'");
  m.ratio = *ratio;
  const auto metric = get_string(params, "metric");
  if (metric && *metric != "bottleneck")
    invalid("metric", "parameter 'metric' must be bottleneck (or omitted) with 'ratio': the ratio is d_B / d_W" +
                          ratio->substr(ratio->size() - 1) + ", got '" + *metric + "'");
  if (find(params, "q")) invalid("q", "parameter 'q' is not taken with 'ratio' (d_B / d_W1 or d_B / d_W2)");
  m.query = with_selection(params, parse_metric("bottleneck"));
  m.denominator = m.query;
  m.denominator->metric = parse_metric(*ratio);
  return m;
}

json describe(const StepQuery& q) { return describe(q.metric, q.dim, q.force, q.essential); }

// ---- runs ------------------------------------------------------------------------------------

[[noreturn]] void unknown_run(const std::string& run) {
  throw Error(rpc::kUnknownRun, "unknown run '" + run + "'", {{"run", run}});
}

// A name no run can have is said so before it is compared with any (a long one is not echoed).
[[noreturn]] void unknown_run(const Registry& registry, const std::string& run) {
  if (const std::string problem = run_id_problem(run); !problem.empty()) invalid("run", "parameter 'run': " + problem);
  std::vector<std::string> names;
  for (const RunSummary& s : registry.runs()) names.push_back(s.run_id);
  const std::vector<std::string> close = close_names(names, run);
  std::string message = "unknown run '" + run + "'";
  if (!close.empty()) {
    message += "; close: ";
    for (std::size_t k = 0; k < close.size(); ++k) message += (k ? ", " : "") + close[k];
  } else {
    message += names.empty() ? "; the server has no runs"
                             : "; the server has " + std::to_string(names.size()) + " run" +
                                   (names.size() == 1 ? "" : "s") + " (runs.list)";
  }
  throw Error(rpc::kUnknownRun, message, {{"run", run}, {"close", close}});
}

[[noreturn]] void unknown_frame(const std::string& run, std::uint32_t index) {
  throw Error(rpc::kUnknownFrame, "run '" + run + "' has no analyzed frame " + std::to_string(index),
              {{"run", run}, {"frame", index}});
}

// The named run, or the newest one when the parameter is omitted.
std::string resolve_run(const Registry& registry, const json& params, std::string_view name) {
  std::string run = get_string(params, name).value_or("");
  if (run.empty()) {
    run = registry.newest_run();
    if (run.empty()) throw Error(rpc::kUnknownRun, "the server has no runs yet", {{"run", nullptr}});
    return run;
  }
  if (!registry.has_run(run)) unknown_run(registry, run);
  return run;
}

[[noreturn]] void no_network(const std::string& run, std::uint32_t index, const std::string& reason) {
  throw Error(rpc::kNoNetwork, reason, {{"run", run}, {"frame", index}, {"reason", reason}});
}

}  // namespace fnet::server
