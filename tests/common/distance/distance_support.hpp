// Helpers for the distance tests: random diagrams, an all-matchings brute force written from the
// definitions alone, the LAMMPS frames' diagrams, and the Python assignment oracle.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "common/distance/essential_convention.hpp"
#include "common/distance/wasserstein.hpp"
#include "common/topology/diagram.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::test {

// The L-infinity distance between two points of the plane, from the definition.
inline double linf(PlanePoint p, PlanePoint q) { return std::max(std::fabs(p.x - q.x), std::fabs(p.y - q.y)); }
// A diagram's points in the plane under the floor convention (never-dying classes die at 0).
inline std::vector<PlanePoint> plane(const Diagram& d) {
  return apply_convention(d, EssentialConvention::floor).points;
}

inline constexpr EssentialConvention kAllConventions[] = {EssentialConvention::floor, EssentialConvention::sentinel,
                                                          EssentialConvention::separate};

// A random diagram: `count` points, births in [0, top], some never-dying, some duplicated,
// coordinates on a coarse grid when `grid` (ties everywhere).
Diagram random_diagram(std::mt19937_64& rng, std::size_t count, double top, bool grid);
// A copy with every coordinate moved by up to `noise` (birth >= death kept), a few points dropped
// and a few added: what consecutive frames look like.
Diagram perturbed(std::mt19937_64& rng, const Diagram& d, double noise);
Diagram scaled(const Diagram& d, double c);  // every coordinate but the -1 of never-dying classes

// Brute force over every matching (each point of a to a distinct point of b or the diagonal).
// q == 0 means the bottleneck. +inf when separate and the counts of never-dying classes differ.
// The sums of q-th powers are taken in long double relative to their largest term: exact to
// rounding for any q (1e6 included) and any scale.
double brute_force_distance(const Diagram& a, const Diagram& b, double q, EssentialConvention convention);

// PD0 and PD1 of a LAMMPS reference frame (tests/data), normal or tangential forces.
struct FrameDiagramsPair {
  Diagram pd0, pd1;
};
FrameDiagramsPair lammps_diagrams(int frame, bool tangential);

// Runs assignment_oracle.py on the two diagrams; returns {metric -> value} (NaN for null).
// metrics: "bottleneck" or a q such as "1", "2".
std::vector<double> oracle_distances(const Diagram& a, const Diagram& b, EssentialConvention convention,
                                     const std::vector<std::string>& metrics);
bool oracle_available();

// The Wasserstein solver's matching and an LP-dual lower bound computed here from its potentials,
// every pair and hub arc scanned (dual_certificate_test.cpp explains the bound). Points as the
// distances see them (apply_convention), neither side empty; costs (length / unit)^q.
struct Certificate {
  double primal = 0, dual = 0;
  bool matching_valid = true;
};
// solver: network_simplex certifies that solver's answer (simplex_transport.hpp), any other the
// shortest paths' (diagonal_flow.hpp).
Certificate certify_wasserstein(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double q,
                                double unit = 1, WassersteinSolver solver = WassersteinSolver::shortest_paths);

using fnet::testing::TempDir;  // tests/unit/temp_dir.hpp

}  // namespace fnet::test
