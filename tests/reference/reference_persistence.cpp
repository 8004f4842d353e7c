#include "tests/reference/reference_persistence.hpp"

#include <algorithm>
#include <map>

#include "tests/reference/flag_filtration.hpp"
#include "tests/reference/standard_reduction.hpp"

namespace fnet::reference {
namespace {

// The boundary of every simplex as rows of the filtration: the faces obtained by dropping one vertex.
std::vector<Column> boundary_matrix(const Filtration& filtration) {
  std::map<std::vector<std::uint32_t>, std::size_t> position;
  for (std::size_t k = 0; k < filtration.simplices.size(); ++k) position[filtration.simplices[k].vertices] = k;
  std::vector<Column> boundary(filtration.simplices.size());
  for (std::size_t k = 0; k < filtration.simplices.size(); ++k) {
    const auto& vertices = filtration.simplices[k].vertices;
    if (vertices.size() == 1) continue;
    for (std::size_t drop = 0; drop < vertices.size(); ++drop) {
      std::vector<std::uint32_t> face;
      for (std::size_t m = 0; m < vertices.size(); ++m)
        if (m != drop) face.push_back(vertices[m]);
      boundary[k].push_back(position.at(face));  // a face missing from the complex would be a bug
    }
    std::sort(boundary[k].begin(), boundary[k].end());
  }
  return boundary;
}

void sort_birth_then_death_descending(Diagram& diagram) {
  std::sort(diagram.begin(), diagram.end(), [](const PersistencePoint& a, const PersistencePoint& b) {
    return a.birth != b.birth ? a.birth > b.birth : a.death > b.death;
  });
}

Diagrams diagrams_of(const Filtration& filtration) {
  const auto& simplices = filtration.simplices;
  const auto lowest = reduce_lowest_rows(boundary_matrix(filtration));

  Diagrams out;
  out.vertices = filtration.vertices;
  out.edges = filtration.edges;
  out.triangles = filtration.triangles;
  out.mean_force = filtration.mean_force;
  const auto diagram_of = [&](std::size_t dimension) -> Diagram* {
    return dimension == 0 ? &out.pd0 : dimension == 1 ? &out.pd1 : nullptr;
  };

  std::vector<bool> kills(simplices.size(), false), is_killed(simplices.size(), false);
  for (std::size_t j = 0; j < simplices.size(); ++j) {
    if (!lowest[j]) continue;
    const std::size_t i = *lowest[j];
    kills[j] = true;
    is_killed[i] = true;
    Diagram* diagram = diagram_of(simplices[i].dimension());
    if (diagram && simplices[i].value != simplices[j].value)
      diagram->push_back({simplices[i].value, simplices[j].value});
  }
  // A positive simplex (column reduced to zero) that nothing kills is a class that never dies.
  for (std::size_t i = 0; i < simplices.size(); ++i) {
    if (kills[i] || is_killed[i]) continue;
    if (Diagram* diagram = diagram_of(simplices[i].dimension())) diagram->push_back({simplices[i].value, kNeverDies});
  }
  sort_birth_then_death_descending(out.pd0);
  sort_birth_then_death_descending(out.pd1);
  return out;
}

}  // namespace

std::vector<PairedPoint> persistence_pairs(const Frame& frame, ForceKind kind, double mean) {
  const Filtration filtration = flag_filtration(frame, kind, mean);
  const auto& simplices = filtration.simplices;
  const auto lowest = reduce_lowest_rows(boundary_matrix(filtration));
  std::vector<PairedPoint> out;
  std::vector<bool> paired(simplices.size(), false);
  for (std::size_t j = 0; j < simplices.size(); ++j) {
    if (!lowest[j]) continue;
    const std::size_t i = *lowest[j];
    paired[i] = paired[j] = true;
    if (simplices[i].dimension() < 2 && simplices[i].value != simplices[j].value)
      out.push_back({simplices[i].dimension(), simplices[i].value, simplices[j].value, simplices[i].vertices,
                     simplices[j].vertices});
  }
  for (std::size_t i = 0; i < simplices.size(); ++i)
    if (!paired[i] && simplices[i].dimension() < 2)
      out.push_back({simplices[i].dimension(), simplices[i].value, kNeverDies, simplices[i].vertices, {}});
  return out;
}

Diagrams persistence(const Frame& frame, ForceKind kind) { return diagrams_of(flag_filtration(frame, kind)); }

Diagrams persistence(const Frame& frame, ForceKind kind, double mean) {
  return diagrams_of(flag_filtration(frame, kind, mean));
}

}  // namespace fnet::reference
