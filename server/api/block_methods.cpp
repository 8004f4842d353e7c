#include "server/api/block_methods.hpp"

#include <chrono>
#include <limits>

#include "common/analysis/blocks.hpp"
#include "server/api/api_params.hpp"

namespace fnet::server {
namespace {

using rpc::Error;

int get_k(const json& params) {
  const json* v = find(params, "k");
  if (!v) return 2;
  const std::string range = "an integer from " + std::to_string(kMinBlocks) + " to " + std::to_string(kMaxBlocks);
  if (!v->is_number_integer()) wrong_type("k", range.c_str(), *v);
  const bool fits = v->is_number_unsigned()
                        ? v->get<std::uint64_t>() <= static_cast<std::uint64_t>(kMaxBlocks)
                        : v->get<std::int64_t>() >= kMinBlocks && v->get<std::int64_t>() <= kMaxBlocks;
  if (!fits || v->get<std::int64_t>() < kMinBlocks)
    invalid("k", "parameter 'k' must be " + range + " (got " + v->dump() + ")");
  return v->get<int>();
}

json bounds_json(const BlockCell& c) { return json::array({c.bounds[0], c.bounds[1], c.bounds[2], c.bounds[3]}); }

}  // namespace

json blocks_get(const Registry& registry, const json& params) {
  const std::uint32_t frame_a = require_index(params, "frame");
  const std::uint32_t frame_b = require_index(params, "other_frame");
  const int k = get_k(params);
  const StepQuery query = get_step_query(params);
  const auto& [metric, dim, force, essential] = query;
  const std::string run = resolve_run(registry, params);
  if (!registry.frame(run, frame_a)) unknown_frame(run, frame_a);
  if (!registry.frame(run, frame_b)) unknown_frame(run, frame_b);
  const auto start = std::chrono::steady_clock::now();
  const Frame a = stored_network(registry, run, frame_a), b = stored_network(registry, run, frame_b);
  const auto split = [&](const Frame& f, std::uint32_t index) {
    try {
      return split_into_blocks(f, k);
    } catch (const std::invalid_argument& e) {  // a stored frame without its grains' positions
      throw Error(rpc::kNoNetwork, e.what(), {{"run", run}, {"frame", index}, {"reason", e.what()}});
    }
  };
  const std::vector<BlockCell> cells_a = split(a, frame_a), cells_b = split(b, frame_b);
  const std::vector<BlockDistance> d = block_distances(cells_a, cells_b, metric.distance(), dim, force, essential);

  json cells = json::array();
  std::size_t largest = 0;
  const auto key = [&](std::size_t c) {
    return d[c].distance.infinite ? std::numeric_limits<double>::infinity() : d[c].distance.value;
  };
  for (std::size_t c = 0; c < d.size(); ++c) {
    const DistanceResult& r = d[c].distance;
    if (key(c) > key(largest)) largest = c;
    cells.push_back({{"row", cells_a[c].row},
                     {"col", cells_a[c].col},
                     {"bounds", json::array({bounds_json(cells_a[c]), bounds_json(cells_b[c])})},
                     {"contacts", json::array({cells_a[c].contacts.size(), cells_b[c].contacts.size()})},
                     {"points", json::array({d[c].points_a, d[c].points_b})},
                     {"value", r.infinite ? json(nullptr) : json(r.value)},
                     {"infinite", r.infinite}});
  }
  json out = describe(metric, dim, force, essential);
  out["run"] = run;
  out["frame"] = frame_a;
  out["other_frame"] = frame_b;
  out["k"] = k;
  out["cells"] = cells;
  out["largest"] = {{"row", cells_a[largest].row},
                    {"col", cells_a[largest].col},
                    {"value", d[largest].distance.infinite ? json(nullptr) : json(d[largest].distance.value)}};
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace fnet::server
