#include "tests/support/gudhi_persistence.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>  // GUDHI 3.7's Persistent_cohomology.h uses std::cout without including it
#include <vector>

#include <gudhi/Persistent_cohomology.h>
#include <gudhi/Simplex_tree.h>
#include <gudhi/graph_simplicial_complex.h>

namespace fnet::testing {
namespace {

// Full-featured (double filtration values: exact comparison with fnet) with contiguous vertex ids,
// which lets the tree index vertices directly; both are what a careful GUDHI user would pick.
struct FlagTreeOptions : Gudhi::Simplex_tree_options_full_featured {
  static const bool contiguous_vertices = true;
};
using Tree = Gudhi::Simplex_tree<FlagTreeOptions>;
using Graph = Gudhi::Proximity_graph<Tree>;
using Cohomology = Gudhi::persistent_cohomology::Persistent_cohomology<Tree, Gudhi::persistent_cohomology::Field_Zp>;

Diagram superlevel(const std::vector<std::pair<double, double>>& intervals) {
  Diagram out;
  out.reserve(intervals.size());
  for (const auto& [b, d] : intervals) {
    const PersistencePoint p{-b, std::isinf(d) ? kNeverDies : -d};
    if (p.birth != p.death) out.push_back(p);
  }
  sort_canonical(out);
  return out;
}

}  // namespace

FrameDiagrams gudhi_persistence(std::size_t vertex_count, std::span<const Edge> edges) {
  std::vector<double> vertex_value(vertex_count, 0.0);
  for (const Edge& e : edges) {
    vertex_value[e.u] = std::max(vertex_value[e.u], e.value);
    vertex_value[e.v] = std::max(vertex_value[e.v], e.value);
  }
  Graph graph(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v)
    boost::put(Gudhi::vertex_filtration_t(), graph, static_cast<int>(v), -vertex_value[v]);
  for (const Edge& e : edges) boost::add_edge(static_cast<int>(e.u), static_cast<int>(e.v), -e.value, graph);

  Tree tree;
  tree.insert_graph(graph);
  tree.expansion(2);
  // GUDHI skips the top dimension of the complex unless asked: a frame without triangles would
  // lose its whole PD1. With triangles present, H2 (which fnet does not report) is left out.
  Cohomology cohomology(tree, /*persistence_dim_max=*/tree.dimension() < 2);
  cohomology.init_coefficients(2);
  cohomology.compute_persistent_cohomology(0);

  FrameDiagrams out;
  out.vertices = vertex_count;
  out.edges = edges.size();
  out.triangles = tree.num_simplices() - tree.num_vertices() - edges.size();
  out.pd0 = superlevel(cohomology.intervals_in_dimension(0));
  out.pd1 = superlevel(cohomology.intervals_in_dimension(1));
  return out;
}

}  // namespace fnet::testing
