#include "tests/reference/flag_filtration.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace fnet::reference {
namespace {

double magnitude(const Contact& c, ForceKind kind) { return std::fabs(kind == ForceKind::normal ? c.fn : c.ft); }

// Superlevel order: larger value first; on equal values a face before its cofaces (lower
// dimension first); the vertex lists only make the order total and deterministic.
bool enters_before(const Simplex& a, const Simplex& b) {
  if (a.value != b.value) return a.value > b.value;
  if (a.vertices.size() != b.vertices.size()) return a.vertices.size() < b.vertices.size();
  return a.vertices < b.vertices;
}

}  // namespace

double mean_force(const Frame& frame, ForceKind kind) {
  std::vector<double> forces;
  for (const Contact& c : frame.contacts)
    if (magnitude(c, kind) > 0) forces.push_back(magnitude(c, kind));
  if (forces.empty()) return 0;
  std::sort(forces.begin(), forces.end());
  long double sum = 0;
  for (double f : forces) sum += f;
  return static_cast<double>(sum / static_cast<long double>(forces.size()));
}

Filtration flag_filtration(const Frame& frame, ForceKind kind) {
  return flag_filtration(frame, kind, mean_force(frame, kind));
}

Filtration flag_filtration(const Frame& frame, ForceKind kind, double mean) {
  validate(frame);
  Filtration out;
  out.mean_force = mean;

  std::map<std::pair<std::uint32_t, std::uint32_t>, double> edge_value;  // (low, high) -> f
  for (const Contact& c : frame.contacts) {
    const double force = magnitude(c, kind);
    if (!(force > 0)) continue;
    const auto a = static_cast<std::uint32_t>(c.i), b = static_cast<std::uint32_t>(c.j);
    edge_value[{std::min(a, b), std::max(a, b)}] = force / out.mean_force;
  }

  std::vector<double> vertex_value(frame.particle_count, 0.0);
  std::vector<std::set<std::uint32_t>> neighbours(frame.particle_count);
  for (const auto& [uv, value] : edge_value) {
    vertex_value[uv.first] = std::max(vertex_value[uv.first], value);
    vertex_value[uv.second] = std::max(vertex_value[uv.second], value);
    neighbours[uv.first].insert(uv.second);
    neighbours[uv.second].insert(uv.first);
  }

  for (std::uint32_t v = 0; v < frame.particle_count; ++v) out.simplices.push_back({{v}, vertex_value[v]});
  for (const auto& [uv, value] : edge_value) out.simplices.push_back({{uv.first, uv.second}, value});
  // Every triangle u < v < w exactly once: w runs over the common neighbours above v.
  for (const auto& [uv, value] : edge_value) {
    const auto [u, v] = uv;
    for (std::uint32_t w : neighbours[u]) {
      if (w <= v || !neighbours[v].count(w)) continue;
      const double f = std::min({value, edge_value.at({u, w}), edge_value.at({v, w})});
      out.simplices.push_back({{u, v, w}, f});
      ++out.triangles;
    }
  }
  out.vertices = frame.particle_count;
  out.edges = edge_value.size();
  std::sort(out.simplices.begin(), out.simplices.end(), enters_before);
  return out;
}

}  // namespace fnet::reference
