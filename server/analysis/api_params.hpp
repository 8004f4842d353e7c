// The parameter checks every JSON-RPC method of fnet-server shares: each failure is an
// rpc::Error -32602 naming the parameter (data.parameter) and what it must be; unknown runs and
// frames are -32001 and -32002 (proto/api.md). A parameter given as null is taken as omitted.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/analysis/metric_vocabulary.hpp"
#include "proto/json_rpc.hpp"
#include "server/analysis/run_registry.hpp"

namespace fnet::server {

[[noreturn]] void invalid(std::string_view name, const std::string& message);
[[noreturn]] void wrong_type(std::string_view name, const char* expected, const nlohmann::json& got);

// The parameter, or null when it is absent or null.
const nlohmann::json* find(const nlohmann::json& params, std::string_view name);

std::optional<std::string> get_string(const nlohmann::json& params, std::string_view name);
// An integer 0 ... 2^32 - 1 (frame indices, subscription ids).
std::optional<std::uint32_t> get_index(const nlohmann::json& params, std::string_view name);
std::uint32_t require_index(const nlohmann::json& params, std::string_view name);
std::optional<double> get_number(const nlohmann::json& params, std::string_view name);

// dim (default 0), force (default normal), essential (default floor), metric with q (required).
int get_dim(const nlohmann::json& params);
ForceKind get_force(const nlohmann::json& params);
EssentialConvention get_essential(const nlohmann::json& params);
MetricChoice get_metric(const nlohmann::json& params);

// What a distance answer says it measured: metric, q (Wasserstein only), dim, force, essential.
nlohmann::json describe(const MetricChoice& m, int dim, ForceKind force, EssentialConvention essential);

[[noreturn]] void unknown_run(const std::string& run);
[[noreturn]] void unknown_frame(const std::string& run, std::uint32_t index);

// The named run, or the newest one when the parameter is omitted.
std::string resolve_run(const Registry& registry, const nlohmann::json& params, std::string_view name = "run");

}  // namespace fnet::server
