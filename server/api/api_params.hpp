// The parameter helpers of the JSON-RPC methods: every failure names the parameter and what it
// must be (error -32602, data.parameter), before the method does any work.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/analysis/metric_vocabulary.hpp"
#include "common/analysis/step_series.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/force_network.hpp"
#include "proto/json_rpc.hpp"
#include "server/registry/run_registry.hpp"

namespace fnet::server {

using json = nlohmann::json;

[[noreturn]] void invalid(std::string_view name, const std::string& message);
[[noreturn]] void wrong_type(std::string_view name, const char* expected, const json& got);
// While one lives, the running method reads only the parameters it declared (Method::params):
// find() throws std::logic_error for any other, so that what a method declares, and what the
// unknown-parameter check and proto/api.md hold it to, is what it reads.
class ReadingParams {
 public:
  explicit ReadingParams(std::span<const std::string_view> declared);
  ~ReadingParams();
  ReadingParams(const ReadingParams&) = delete;
  ReadingParams& operator=(const ReadingParams&) = delete;

 private:
  std::span<const std::string_view> outer_;
  bool outer_in_method_;
};

// A parameter given as null is taken as omitted.
const json* find(const json& params, std::string_view name);
std::optional<std::string> get_string(const json& params, std::string_view name);
std::optional<std::uint32_t> get_index(const json& params, std::string_view name);
std::uint32_t require_index(const json& params, std::string_view name);
std::optional<double> get_number(const json& params, std::string_view name);
int get_dim(const json& params);
ForceKind get_force(const json& params);
EssentialConvention get_essential(const json& params);
MetricChoice get_metric(const json& params);
json describe(const MetricChoice& m, int dim, ForceKind force, EssentialConvention essential);
// metric (with q), dim, force and essential: the one reading of the quartet every method that
// measures a distance takes.
StepQuery get_step_query(const json& params);
// The quartet, or with `ratio` (wasserstein1 | wasserstein2) the ratio d_B / d_Wq: the metric may
// then be omitted and must be the bottleneck if given, and q is not taken.
SeriesMeasure get_series_measure(const json& params);
json describe(const StepQuery& query);

[[noreturn]] void unknown_run(const std::string& run);
// The same error, its message and data.close naming the server's runs closest to `run`.
[[noreturn]] void unknown_run(const Registry& registry, const std::string& run);
[[noreturn]] void unknown_frame(const std::string& run, std::uint32_t index);
// Error -32005: a committed frame's force network cannot be had; names the run, the frame and why.
[[noreturn]] void no_network(const std::string& run, std::uint32_t index, const std::string& reason);

// The named run, or the newest one when the parameter is omitted.
std::string resolve_run(const Registry& registry, const json& params, std::string_view name = "run");

}  // namespace fnet::server
