#include "server/api/block_methods.hpp"

#include "common/analysis/blocks.hpp"
#include "server/api/api_params.hpp"
#include "server/api/registry_frames.hpp"
#include "server/api/served_query.hpp"
#include "server/query/block_query.hpp"

namespace fnet::server {
namespace {

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

json distance_value(const DistanceResult& d) { return d.infinite ? json(nullptr) : json(d.value); }

}  // namespace

json blocks_get(const Registry& registry, const json& params) {
  query::BlockRequest r;
  r.frame = require_index(params, "frame");
  r.other_frame = require_index(params, "other_frame");
  r.k = get_k(params);
  r.measure = get_step_query(params);
  r.run = resolve_run(registry, params);
  const query::BlockAnswer b = served([&] { return query::block_query(RegistryFrames(registry), r); });

  json cells = json::array();
  for (std::size_t c = 0; c < b.distances.size(); ++c) {
    const BlockCell &cell = b.cells[c], &other = b.other_cells[c];
    const DistanceResult& d = b.distances[c].distance;
    cells.push_back({{"row", cell.row},
                     {"col", cell.col},
                     {"bounds", json::array({bounds_json(cell), bounds_json(other)})},
                     {"contacts", json::array({cell.contacts.size(), other.contacts.size()})},
                     {"points", json::array({b.distances[c].points_a, b.distances[c].points_b})},
                     {"value", distance_value(d)},
                     {"infinite", d.infinite}});
  }
  json out = describe(r.measure);
  out["run"] = r.run;
  out["frame"] = r.frame;
  out["other_frame"] = r.other_frame;
  out["k"] = r.k;
  out["cells"] = cells;
  out["largest"] = {{"row", b.cells[b.largest].row},
                    {"col", b.cells[b.largest].col},
                    {"value", distance_value(b.distances[b.largest].distance)}};
  out["seconds"] = b.seconds;
  return out;
}

}  // namespace fnet::server
