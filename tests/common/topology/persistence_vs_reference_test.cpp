// The fast path (build_network + compute_persistence) against the brute-force reference on
// thousands of random frames: the mean force to 1e-15, then diagrams bit for bit and simplex counts
// (see matches_reference).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "common/codec/frame_csv.hpp"
#include "tests/reference/reference_persistence.hpp"
#include "tests/support/contact_graphs.hpp"
#include "tests/support/diagram_checks.hpp"
#include "tests/support/random_forces.hpp"

namespace fnet::testing {
namespace {

constexpr ForceKind kKinds[] = {ForceKind::normal, ForceKind::tangential};

std::size_t uniform(std::size_t lo, std::size_t hi, std::mt19937_64& rng) {
  return std::uniform_int_distribution<std::size_t>(lo, hi)(rng);
}
double uniform_real(double lo, double hi, std::mt19937_64& rng) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Compares `count` frames from `make`, both force kinds; stops at the first mismatch so the log
// holds one reproducible case.
template <class Make>
void compare_many(std::uint64_t seed, int count, Make make) {
  std::mt19937_64 rng(seed);
  for (int k = 0; k < count; ++k) {
    const Frame frame = make(rng);
    for (ForceKind kind : kKinds) ASSERT_TRUE(matches_reference(frame, kind)) << "case " << k << ", seed " << seed;
  }
}

std::size_t few_rattlers(std::mt19937_64& rng) { return uniform(0, 3, rng) == 0 ? uniform(1, 3, rng) : 0; }

TEST(PersistenceVsReference, PlanarTriangularLattices) {
  compare_many(101, 4000, [](auto& rng) {
    const Graph g = triangular_lattice(uniform(1, 6, rng), uniform(2, 6, rng), uniform_real(0.5, 1.0, rng), rng);
    return frame_from_graph(g, random_style(rng), few_rattlers(rng), rng);
  });
}

TEST(PersistenceVsReference, PlanarSquareLatticesWithUnfilledLoops) {
  compare_many(102, 4000, [](auto& rng) {
    const Graph g = square_lattice(uniform(2, 6, rng), uniform(2, 6, rng), uniform_real(0.6, 1.0, rng),
                                   uniform_real(0.0, 0.6, rng), rng);
    return frame_from_graph(g, random_style(rng), few_rattlers(rng), rng);
  });
}

TEST(PersistenceVsReference, RandomGeometricGraphsOfSmallDegree) {
  compare_many(103, 3000, [](auto& rng) {
    const std::size_t n = uniform(3, 60, rng);
    const double degree = uniform_real(2.0, 6.0, rng);  // mean degree ~ n pi r^2
    const Graph g = random_geometric(n, std::sqrt(degree / (std::numbers::pi * static_cast<double>(n))), rng);
    return frame_from_graph(g, random_style(rng), 0, rng);
  });
}

TEST(PersistenceVsReference, NestedSeparatingTriangles) {
  compare_many(104, 3000, [](auto& rng) {
    return frame_from_graph(apollonian(uniform(1, 30, rng), rng), random_style(rng), few_rattlers(rng), rng);
  });
}

TEST(PersistenceVsReference, NonPlanarDenseGraphs) {
  compare_many(105, 5000, [](auto& rng) {
    const Graph g = random_dense(uniform(4, 11, rng), uniform_real(0.3, 0.95, rng), rng);
    return frame_from_graph(g, random_style(rng), few_rattlers(rng), rng);
  });
}

TEST(PersistenceVsReference, CompleteGraphsK4K5K6) {
  compare_many(106, 3000,
               [](auto& rng) { return frame_from_graph(complete(uniform(4, 6, rng)), random_style(rng), 0, rng); });
}

TEST(PersistenceVsReference, K33PlusTriangles) {
  compare_many(107, 3000, [](auto& rng) {
    return frame_from_graph(bipartite_k33_with_chords(uniform(0, 6, rng), rng), random_style(rng), 0, rng);
  });
}

TEST(PersistenceVsReference, PlanarAndNonPlanarPiecesSideBySide) {
  compare_many(108, 2000, [](auto& rng) {
    const Graph g = disjoint_union(complete(uniform(4, 5, rng)), disjoint_union(apollonian(uniform(0, 8, rng), rng),
                                                                                triangular_lattice(3, 3, 0.8, rng)));
    return frame_from_graph(g, random_style(rng), few_rattlers(rng), rng);
  });
}

// Ties are where a tie-breaking dependence would show: values from {1, 2} or {1, 2, 3} only.
TEST(PersistenceVsReference, ManyTiesFromATinySetOfValues) {
  compare_many(109, 4000, [](auto& rng) {
    const Graph g = uniform(0, 1, rng) == 0 ? random_dense(uniform(4, 10, rng), 0.6, rng)
                                            : triangular_lattice(uniform(2, 5, rng), uniform(2, 5, rng), 0.85, rng);
    return frame_from_graph(g, ForceStyle{uniform(2, 3, rng), 0, 0, 0}, 0, rng);
  });
}

// Values that differ only in their last bits: any loss of precision in ordering shows here.
TEST(PersistenceVsReference, NearTiesDifferingInTheLastBits) {
  compare_many(115, 3000, [](auto& rng) {
    const Graph g = uniform(0, 1, rng) == 0 ? random_dense(uniform(4, 10, rng), 0.6, rng)
                                            : triangular_lattice(uniform(2, 5, rng), uniform(2, 5, rng), 0.85, rng);
    return frame_from_graph(g, ForceStyle{uniform(0, 2, rng), 0, 0, 3}, 0, rng);
  });
}

// From 256 edges on, build_network sorts by radix instead of comparisons: compare there too.
TEST(PersistenceVsReference, LargeFramesTakeTheRadixSortPath) {
  compare_many(116, 60, [](auto& rng) {
    const ForceStyle styles[] = {{}, {3, 0.05, 0.1, 0}, {2, 0, 0, 2}, {1, 0, 0, 0}};
    const Graph g = uniform(0, 1, rng) == 0 ? triangular_lattice(uniform(10, 16, rng), uniform(10, 16, rng), 0.9, rng)
                                            : random_dense(uniform(30, 40, rng), 0.45, rng);
    return frame_from_graph(g, styles[uniform(0, 3, rng)], uniform(0, 5, rng), rng);
  });
}

// Vertices with dozens of neighbours, and edges between two of them: the triangle search must find
// every common neighbour however long both lists are.
TEST(PersistenceVsReference, HighDegreeHubs) {
  compare_many(117, 300, [](auto& rng) {
    const Graph g = hubs_on_a_ring(uniform(8, 60, rng), uniform(1, 4, rng));
    return frame_from_graph(g, random_style(rng), 0, rng);
  });
}

TEST(PersistenceVsReference, LargeCompleteGraphs) {
  compare_many(118, 40,
               [](auto& rng) { return frame_from_graph(complete(uniform(10, 24, rng)), random_style(rng), 0, rng); });
}

// Forces over 600 decades: normalized values reach subnormals and underflow to 0, where the
// order of raw forces and of normalized values part ways.
TEST(PersistenceVsReference, ExtremeRangeOfForces) {
  std::mt19937_64 rng(119);
  for (int k = 0; k < 1000; ++k) {
    Frame frame = frame_from_graph(random_dense(uniform(3, 9, rng), 0.7, rng), ForceStyle{}, 0, rng);
    for (Contact& c : frame.contacts) {
      c.fn = std::exp(uniform_real(-700, 700, rng));
      c.ft = uniform(0, 1, rng) ? 1e-320 * static_cast<double>(uniform(1, 3, rng)) : 1e300;  // subnormal ties
    }
    for (ForceKind kind : kKinds) ASSERT_TRUE(matches_reference(frame, kind)) << "case " << k;
  }
}

TEST(PersistenceVsReference, SingleDistinctValue) {
  compare_many(110, 1500, [](auto& rng) {
    const Graph g =
        uniform(0, 1, rng) == 0 ? random_dense(uniform(3, 10, rng), 0.7, rng) : apollonian(uniform(0, 15, rng), rng);
    return frame_from_graph(g, ForceStyle{1, 0, 0, 0}, few_rattlers(rng), rng);
  });
}

// A contact with fn = 0 (or ft = 0) is not an edge of that network; half the contacts are such.
TEST(PersistenceVsReference, ZeroForcesAreNotEdges) {
  std::mt19937_64 rng(111);
  for (int k = 0; k < 800; ++k) {
    const Frame frame = frame_from_graph(triangular_lattice(uniform(2, 5, rng), uniform(2, 5, rng), 0.9, rng),
                                         ForceStyle{0, 0.5, 0, 0}, 0, rng);
    for (ForceKind kind : kKinds) {
      ASSERT_TRUE(matches_reference(frame, kind)) << "case " << k;
      std::size_t positive = 0;
      for (const Contact& c : frame.contacts) positive += (kind == ForceKind::normal ? c.fn : c.ft) != 0;
      ASSERT_EQ(fast_path(frame, kind).edges, positive) << describe(frame);
    }
  }
}

// Tensile contacts (fn < 0) enter with |fn|: the frame with fn replaced by |fn| has the same diagrams.
TEST(PersistenceVsReference, NegativeNormalForceUsesItsMagnitude) {
  std::mt19937_64 rng(112);
  for (int k = 0; k < 800; ++k) {
    const Frame frame =
        frame_from_graph(random_dense(uniform(4, 9, rng), 0.6, rng), ForceStyle{0, 0.1, 0.5, 0}, 0, rng);
    ASSERT_TRUE(matches_reference(frame, ForceKind::normal)) << "case " << k;
    Frame magnitudes = frame;
    for (Contact& c : magnitudes.contacts) c.fn = std::fabs(c.fn);
    const FrameDiagrams signed_fn = fast_path(frame, ForceKind::normal),
                        abs_fn = fast_path(magnitudes, ForceKind::normal);
    ASSERT_EQ(signed_fn.pd0, abs_fn.pd0) << describe(frame);
    ASSERT_EQ(signed_fn.pd1, abs_fn.pd1) << describe(frame);
  }
}

TEST(PersistenceVsReference, EmptyFramesAndFramesWithoutForce) {
  for (std::size_t n = 0; n < 6; ++n) {
    Frame empty;
    empty.label = "empty";
    empty.particle_count = n;
    for (ForceKind kind : kKinds) {
      ASSERT_TRUE(matches_reference(empty, kind));
      const FrameDiagrams d = fast_path(empty, kind);
      EXPECT_EQ(d.pd0, Diagram(n, PersistencePoint{0.0, kNeverDies})) << "every particle is a rattler";
      EXPECT_TRUE(d.pd1.empty());
    }
  }
  std::mt19937_64 rng(113);
  for (int k = 0; k < 100; ++k) {  // contacts present but every force zero: no edges at all
    const Frame frame = frame_from_graph(random_dense(uniform(2, 8, rng), 0.5, rng), ForceStyle{0, 1.0, 0, 0}, 0, rng);
    for (ForceKind kind : kKinds) {
      ASSERT_TRUE(matches_reference(frame, kind));
      EXPECT_EQ(fast_path(frame, kind).pd0, Diagram(frame.particle_count, PersistencePoint{0.0, kNeverDies}));
    }
  }
}

TEST(PersistenceVsReference, IsolatedParticlesAreRattlers) {
  std::mt19937_64 rng(114);
  for (int k = 0; k < 500; ++k) {
    const std::size_t rattlers = uniform(1, 5, rng);
    const Frame frame = frame_from_graph(apollonian(uniform(0, 10, rng), rng), ForceStyle{0, 0, 0, 0}, rattlers, rng);
    for (ForceKind kind : kKinds) {
      ASSERT_TRUE(matches_reference(frame, kind));
      const Diagram pd0 = fast_path(frame, kind).pd0;
      ASSERT_GE(pd0.size(), rattlers);
      // Canonical order puts the rattlers' (0, -1) last.
      for (std::size_t r = 0; r < rattlers; ++r)
        EXPECT_EQ(pd0[pd0.size() - 1 - r], (PersistencePoint{0.0, kNeverDies}));
    }
  }
}

// Real packings from LAMMPS, from a loose gas of chains to a jammed network with thousands of contacts.
TEST(PersistenceVsReference, LammpsFrames) {
  const std::filesystem::path dir = std::filesystem::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";
  for (int k = 0; k <= 10; ++k) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame_%04d_", k);
    const Frame frame =
        read_frame_csv(dir / (std::string(stem) + "contacts.csv"), dir / (std::string(stem) + "particles.csv"));
    for (ForceKind kind : kKinds) EXPECT_TRUE(matches_reference(frame, kind)) << frame.label;
  }
}

}  // namespace
}  // namespace fnet::testing
