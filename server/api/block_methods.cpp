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

// x_lo, x_hi, y_lo, y_hi; then z_lo, z_hi in 3D.
json bounds_json(const BlockCell& c, bool three_d) {
  json out = json::array({c.bounds[0], c.bounds[1], c.bounds[2], c.bounds[3]});
  if (three_d) out.push_back(c.bounds[4]), out.push_back(c.bounds[5]);
  return out;
}

// {"layer"?, "row", "col"}: the layer only in 3D, so that a 2D answer is as it always was.
json cell_index(const BlockCell& c, bool three_d) {
  json out = json::object();
  if (three_d) out["layer"] = c.layer;
  out["row"] = c.row;
  out["col"] = c.col;
  return out;
}

json distance_value(const DistanceResult& d) { return d.infinite ? json(nullptr) : json(d.value); }

}  // namespace

json blocks_json(const query::BlockRequest& r, const query::BlockAnswer& b) {
  const bool three_d = !b.cells.empty() && b.cells.front().network.dimension == 3;
  json cells = json::array();
  for (std::size_t c = 0; c < b.distances.size(); ++c) {
    const BlockCell &cell = b.cells[c], &other = b.other_cells[c];
    const DistanceResult& d = b.distances[c].distance;
    json out = cell_index(cell, three_d);
    out["bounds"] = json::array({bounds_json(cell, three_d), bounds_json(other, three_d)});
    out["contacts"] = json::array({cell.contacts.size(), other.contacts.size()});
    out["points"] = json::array({b.distances[c].points_a, b.distances[c].points_b});
    out["value"] = distance_value(d);
    out["infinite"] = d.infinite;
    cells.push_back(std::move(out));
  }
  json out = describe(r.measure);
  out["run"] = r.run;
  out["frame"] = r.frame;
  out["other_frame"] = r.other_frame;
  out["k"] = r.k;
  out["dimension"] = three_d ? 3 : 2;
  out["cells"] = cells;
  out["largest"] = cell_index(b.cells[b.largest], three_d);
  out["largest"]["value"] = distance_value(b.distances[b.largest].distance);
  out["seconds"] = b.seconds;
  return out;
}

json blocks_get(const Registry& registry, const json& params) {
  query::BlockRequest r;
  r.frame = require_index(params, "frame");
  r.other_frame = require_index(params, "other_frame");
  r.k = get_k(params);
  r.measure = get_step_query(params);
  r.run = resolve_run(registry, params);
  return blocks_json(r, served([&] { return query::block_query(RegistryFrames(registry), r); }));
}

}  // namespace fnet::server
