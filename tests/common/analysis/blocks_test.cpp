#include "common/analysis/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/fcc_packing.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/synthetic_frame.hpp"

namespace fnet {
namespace {

// The contact point as the documents define it, computed here on its own.
std::pair<double, double> contact_point(const Frame& f, const Contact& c) {
  const Particle& a = f.particles[c.i];
  const Particle& b = f.particles[c.j];
  const double len = std::hypot(b.x - a.x, b.y - a.y);
  return {a.x + a.r * (b.x - a.x) / len, a.y + a.r * (b.y - a.y) / len};
}

Frame line_of_grains(std::size_t n, double r) {
  Frame f;
  f.label = "line";
  f.particle_count = n;
  for (std::size_t g = 0; g < n; ++g) f.particles.push_back({static_cast<double>(g), 0.0, r});
  for (std::size_t g = 0; g + 1 < n; ++g)
    f.contacts.push_back({static_cast<std::int64_t>(g), static_cast<std::int64_t>(g + 1), 1.0 + static_cast<double>(g),
                          0.5 + static_cast<double>(g)});
  return f;
}

// Each cell's distance, for every force, dim and metric, against the exact distance between the
// networks `cell_network(frame, cell)` builds on its own; `also(expected, got, dim)` for more.
template <class CellNetwork, class Also>
void expect_exact_cell_distances(const Frame& a, const Frame& b, const std::vector<BlockCell>& cells_a,
                                 const std::vector<BlockCell>& cells_b, CellNetwork cell_network, Also also) {
  for (const ForceKind force : kForces)
    for (int dim = 0; dim < 2; ++dim)
      for (const Metric metric : kMetrics) {
        const auto got = block_distances(cells_a, cells_b, distance_metric(metric), dim, force);
        ASSERT_EQ(got.size(), cells_a.size());
        for (std::size_t c = 0; c < got.size(); ++c) {
          const FrameDiagramSet ea = analyze_frame(cell_network(a, cells_a[c]));
          const FrameDiagramSet eb = analyze_frame(cell_network(b, cells_b[c]));
          const double expected =
              diagram_distance(diagram_of(ea, force, dim), diagram_of(eb, force, dim), metric).value;
          EXPECT_NEAR(got[c].distance.value, expected, 1e-9 * std::max(1.0, expected))
              << to_string(metric) << " dim " << dim << " " << to_string(force) << " cell " << c;
          also(expected, got[c].distance.value, dim);
        }
      }
}

TEST(Blocks, EveryContactBelongsToExactlyOneCellTheOneHoldingItsContactPoint) {
  const Frame f = testing::lammps_frame(10);
  validate(f);
  for (const int k : {1, 2, 3, 7, 16}) {
    const auto cells = split_into_blocks(f, k);
    ASSERT_EQ(cells.size(), static_cast<std::size_t>(k * k));
    std::vector<std::size_t> all;
    for (const BlockCell& c : cells) {
      EXPECT_EQ(c.network.contacts.size(), c.contacts.size());
      for (const std::size_t n : c.contacts) {
        all.push_back(n);
        const auto [x, y] = contact_point(f, f.contacts[n]);
        EXPECT_GE(x, c.bounds[0]) << "k " << k;
        EXPECT_LE(x, c.bounds[1]) << "k " << k;
        EXPECT_GE(y, c.bounds[2]) << "k " << k;
        EXPECT_LE(y, c.bounds[3]) << "k " << k;
      }
    }
    std::sort(all.begin(), all.end());
    std::vector<std::size_t> expected(f.contacts.size());
    std::iota(expected.begin(), expected.end(), 0);
    EXPECT_EQ(all, expected) << "k " << k;
  }
}

TEST(Blocks, TheDomainIsTheBoundingBoxOfTheDiscs) {
  Frame f = line_of_grains(3, 0.5);
  f.particles[2].r = 2;
  const BlockDomain d = block_domain(f);
  EXPECT_EQ(d.x_lo, -0.5);
  EXPECT_EQ(d.x_hi, 4.0);
  EXPECT_EQ(d.y_lo, -2.0);
  EXPECT_EQ(d.y_hi, 2.0);
}

// Two LAMMPS frames and a 3D packing (an FCC one: full of triangles).
TEST(Blocks, OneCellIsTheWholeFrame) {
  for (const Frame& f : {testing::lammps_frame(0), testing::lammps_frame(10), testing::fcc_frame({.cells = 3})}) {
    validate(f);
    const FrameDiagramSet whole = analyze_frame(f);
    const auto cells = split_into_blocks(f, 1);
    ASSERT_EQ(cells.size(), 1u);
    for (const ForceKind force : kForces) {
      const FrameDiagrams cell = block_diagrams(cells[0], force);
      EXPECT_EQ(cell.pd0, whole[force].pd0) << f.label;
      EXPECT_EQ(cell.pd1, whole[force].pd1) << f.label;
      EXPECT_EQ(cell.vertices, whole[force].vertices);
      EXPECT_EQ(cell.edges, whole[force].edges);
      EXPECT_EQ(cell.triangles, whole[force].triangles);
    }
  }
}

// Each cell's distance equals the exact distance between the networks made of the contacts whose
// contact point lies in the cell, chosen here with the edge rule written out on its own.
TEST(Blocks, CellDistancesAreTheExactDistancesOfTheCellsNetworks) {
  const Frame a = testing::lammps_frame(9), b = testing::lammps_frame(10);
  validate(a), validate(b);
  constexpr int k = 2;
  const auto cells_a = split_into_blocks(a, k), cells_b = split_into_blocks(b, k);
  const auto cell_network = [](const Frame& f, const BlockCell& cell) {
    Frame out;
    out.label = "expected";
    out.particle_count = f.particle_count;  // extra rattlers: zero-length points under floor
    out.particles = f.particles;
    const bool last_col = cell.col == k - 1, last_row = cell.row == k - 1;
    for (const Contact& c : f.contacts) {
      const auto [x, y] = contact_point(f, c);
      const bool in_x = x >= cell.bounds[0] && (last_col ? x <= cell.bounds[1] : x < cell.bounds[1]);
      const bool in_y = y >= cell.bounds[2] && (last_row ? y <= cell.bounds[3] : y < cell.bounds[3]);
      if (in_x && in_y) out.contacts.push_back(c);
    }
    return out;
  };
  expect_exact_cell_distances(a, b, cells_a, cells_b, cell_network, [](double expected, double got, int) {
    EXPECT_GT(expected + got, 0) << "frames 9 and 10 differ in every quarter";
  });
}

TEST(Blocks, EmptyCellsAreAtDistanceZeroFromEachOther) {
  // Contacts only along the bottom row of a 4 x 4 grid: the cells above have no contacts.
  const Frame f = line_of_grains(8, 0.5);
  Frame tall = f;
  tall.particles.push_back({3.5, 10.0, 0.5});  // a rattler far above stretches the domain upward
  tall.particle_count = tall.particles.size();
  Frame other = tall;
  for (Contact& c : other.contacts) c.fn *= 1.0 + 0.1 * static_cast<double>(c.i);
  const auto ca = split_into_blocks(tall, 4), cb = split_into_blocks(other, 4);
  const auto d = block_distances(ca, cb, DistanceMetric::wasserstein(2), 0, ForceKind::normal);
  std::size_t empty = 0;
  for (std::size_t c = 0; c < d.size(); ++c) {
    if (!ca[c].contacts.empty()) continue;
    ++empty;
    EXPECT_EQ(d[c].distance.value, 0.0) << c;
    EXPECT_EQ(d[c].points_a, d[c].points_b) << c;
  }
  EXPECT_EQ(empty, 12u);
  // The rattler is in the top row, in the cell holding its centre, and nowhere else.
  std::size_t holding = 0;
  for (const BlockCell& c : ca) holding += std::count(c.grains.begin(), c.grains.end(), 8u);
  EXPECT_EQ(holding, 1u);
  EXPECT_EQ(std::count(ca[3 * 4 + 2].grains.begin(), ca[3 * 4 + 2].grains.end(), 8u), 1);
}

TEST(Blocks, KFromOneToSixteenOthersRejected) {
  const Frame f = testing::synthetic_frame({.particles = 500});
  EXPECT_EQ(split_into_blocks(f, kMinBlocks).size(), 1u);
  EXPECT_EQ(split_into_blocks(f, kMaxBlocks).size(), 256u);
  for (const int k : {0, 17, -1}) {
    try {
      split_into_blocks(f, k);
      ADD_FAILURE() << "k " << k << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("from 1 to 16"), std::string::npos) << e.what();
    }
  }
}

TEST(Blocks, AFrameWithoutPositionsIsRejectedByName) {
  Frame f;
  f.label = "run r frame 3";
  f.particle_count = 2;
  f.contacts = {{0, 1, 1.0, 1.0}};
  try {
    split_into_blocks(f, 2);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("run r frame 3"), std::string::npos) << e.what();
  }
}

TEST(Blocks, OneGrainSitsInOneCell) {
  Frame f;
  f.label = "one";
  f.particle_count = 1;
  f.particles = {{2.0, 3.0, 0.5}};
  const auto cells = split_into_blocks(f, 2);
  // Its centre is on both middle edges: the larger indices take it.
  for (const BlockCell& c : cells) EXPECT_EQ(c.grains.size(), (c.row == 1 && c.col == 1) ? 1u : 0u);
  const auto d = block_distances(cells, cells, DistanceMetric::bottleneck(), 0, ForceKind::normal);
  for (const BlockDistance& b : d) EXPECT_EQ(b.distance.value, 0.0);
}

TEST(Blocks, AContactOnACellEdgeGoesToTheLargerIndex) {
  // Grains at x = 0 and 2 (r = 1): the domain is [-1, 3] x [-1, 1], its middle edges x = 1 and
  // y = 0, and the contact point (1, 0) lies on both.
  Frame f;
  f.label = "edge";
  f.particle_count = 2;
  f.particles = {{0.0, 0.0, 1.0}, {2.0, 0.0, 1.0}};
  f.contacts = {{0, 1, 1.0, 1.0}};
  const auto cells = split_into_blocks(f, 2);
  EXPECT_EQ(cells[3].contacts, std::vector<std::size_t>{0});
  EXPECT_EQ(cells[3].row, 1);
  EXPECT_EQ(cells[3].col, 1);
  EXPECT_EQ(cells[3].bounds, (std::array<double, 6>{1.0, 3.0, 0.0, 1.0, 0.0, 0.0}));
}

TEST(Blocks, GrainsOnALineOfZeroHeightMakeOneRow) {
  // Radii 0: the domain has no height, so every contact is in row 0, spread over the columns.
  const Frame f = line_of_grains(9, 0.0);
  validate(f);
  const auto cells = split_into_blocks(f, 4);
  std::size_t contacts = 0;
  for (const BlockCell& c : cells) {
    if (c.row != 0) {
      EXPECT_TRUE(c.contacts.empty() && c.grains.empty()) << c.row << "," << c.col;
    } else {
      EXPECT_FALSE(c.contacts.empty()) << c.col;
    }
    contacts += c.contacts.size();
  }
  EXPECT_EQ(contacts, f.contacts.size());
  // With radii the line has a height; still every grain is in the middle rows' boundary row 2.
  const auto thick = split_into_blocks(line_of_grains(9, 0.5), 4);
  for (const BlockCell& c : thick) EXPECT_EQ(c.contacts.empty(), c.row != 2) << c.row << "," << c.col;
}

// ---- 3D frames: k x k x k cells ----

// The contact point in 3D, computed here on its own.
std::array<double, 3> contact_point_3d(const Frame& f, const Contact& c) {
  const Particle& a = f.particles[c.i];
  const Particle& b = f.particles[c.j];
  const double len = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) + (b.z - a.z) * (b.z - a.z));
  return {a.x + a.r * (b.x - a.x) / len, a.y + a.r * (b.y - a.y) / len, a.z + a.r * (b.z - a.z) / len};
}

// Whether point p lies in a cell of a k-grid by the face rule written out: [lo, hi), the last
// cell along an axis [lo, hi].
bool in_cell(const BlockCell& c, int k, const std::array<double, 3>& p) {
  const int index[3] = {c.col, c.row, c.layer};
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = c.bounds[2 * axis], hi = c.bounds[2 * axis + 1];
    if (!(p[axis] >= lo && (index[axis] == k - 1 ? p[axis] <= hi : p[axis] < hi))) return false;
  }
  return true;
}

TEST(Blocks3D, TheDomainIsTheBoundingBoxOfTheSpheres) {
  Frame f;
  f.label = "spheres";
  f.dimension = 3;
  f.particle_count = 3;
  f.particles = {{0.0, 0.0, 0.5, 1.0}, {1.0, 0.0, 0.5, -2.0}, {0.0, 3.0, 2.0, 4.0}};
  const BlockDomain d = block_domain(f);
  EXPECT_EQ(d.x_lo, -2.0);
  EXPECT_EQ(d.x_hi, 2.0);
  EXPECT_EQ(d.y_lo, -0.5);
  EXPECT_EQ(d.y_hi, 5.0);
  EXPECT_EQ(d.z_lo, -2.5);
  EXPECT_EQ(d.z_hi, 6.0);
  // The same positions read as 2D ignore z: the grid stays k x k.
  f.dimension = 2;
  EXPECT_EQ(block_domain(f).z_lo, 0.0);
  EXPECT_EQ(block_domain(f).z_hi, 0.0);
}

TEST(Blocks3D, AContactOnTheMiddleFacesGoesToTheLargestIndexInEveryAxis) {
  // Spheres at z = 0 and 2 (r = 1): the domain is [-1, 1] x [-1, 1] x [-1, 3], its middle faces
  // x = 0, y = 0, z = 1, and the contact point (0, 0, 1) lies on all three.
  Frame f;
  f.label = "faces";
  f.dimension = 3;
  f.particle_count = 2;
  f.particles = {{0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 1.0, 2.0}};
  f.contacts = {{0, 1, 1.0, 1.0}};
  validate(f);
  const auto cells = split_into_blocks(f, 2);
  ASSERT_EQ(cells.size(), 8u);
  for (std::size_t c = 0; c < 8; ++c) {
    EXPECT_EQ(cells[c].layer, static_cast<int>(c / 4)) << c;
    EXPECT_EQ(cells[c].row, static_cast<int>(c / 2 % 2)) << c;
    EXPECT_EQ(cells[c].col, static_cast<int>(c % 2)) << c;
    EXPECT_EQ(cells[c].contacts.empty(), c != 7) << c;
  }
  EXPECT_EQ(cells[7].bounds, (std::array<double, 6>{0.0, 1.0, 0.0, 1.0, 1.0, 3.0}));
  EXPECT_EQ(cells[0].bounds, (std::array<double, 6>{-1.0, 0.0, -1.0, 0.0, -1.0, 1.0}));
  EXPECT_EQ(cells[7].network.dimension, 3);
  EXPECT_NE(cells[7].network.label.find("cell (1, 1, 1)"), std::string::npos) << cells[7].network.label;
}

// Eight clusters, one per octant of a cube: in the octant of cell index n (layer·4 + row·2 + col)
// a chain of n + 1 touching spheres along x, so n contacts; and a rattler in each corner of the
// cube, which fixes the domain [-6.25, 6.25]^3 and so the middle faces at 0.
Frame octant_chains() {
  Frame f;
  f.label = "octants";
  f.dimension = 3;
  const double r = 0.25;
  for (int n = 0; n < 8; ++n) {
    const double sx = n % 2 ? 1 : -1, sy = n / 2 % 2 ? 1 : -1, sz = n / 4 ? 1 : -1;
    f.particles.push_back({6 * sx, 6 * sy, r, 6 * sz});  // the corner rattler
    const std::size_t first = f.particles.size();
    for (int g = 0; g <= n; ++g) f.particles.push_back({3 * sx - 0.5 * n / 2.0 + 0.49 * g, 3 * sy, r, 3 * sz});
    for (int g = 0; g < n; ++g)
      f.contacts.push_back(
          {static_cast<std::int64_t>(first + g), static_cast<std::int64_t>(first + g + 1), 1.0 + g + n, 0.5 + g});
  }
  f.particle_count = f.particles.size();
  return f;
}

TEST(Blocks3D, EachOctantHoldsTheContactsAndGrainsCountedByHand) {
  const Frame f = octant_chains();
  validate(f);
  const auto cells = split_into_blocks(f, 2);
  ASSERT_EQ(cells.size(), 8u);
  for (std::size_t n = 0; n < 8; ++n) {
    EXPECT_EQ(cells[n].contacts.size(), n) << "cell " << n;
    EXPECT_EQ(cells[n].grains.size(), n + 2) << "cell " << n << ": its chain and its corner";
    EXPECT_EQ(cells[n].network.contacts.size(), n);
    for (const double b : {cells[n].bounds[0], cells[n].bounds[2], cells[n].bounds[4]})
      EXPECT_TRUE(b == -6.25 || b == 0.0) << b;
  }
  for (std::size_t n = 0; n < 8; ++n) {
    const FrameDiagrams d = block_diagrams(cells[n], ForceKind::normal);
    EXPECT_EQ(d.vertices, n + 2) << n;
    EXPECT_EQ(d.edges, n) << n;
  }
  // k = 4: the edges are at -6.25, -3.125, 0, 3.125, 6.25; every chain lies at y, z = ±3, so in
  // rows and layers 1 (at -3) and 2 (at +3) only.
  const auto fine = split_into_blocks(f, 4);
  ASSERT_EQ(fine.size(), 64u);
  std::size_t contacts = 0;
  for (const BlockCell& c : fine) {
    contacts += c.contacts.size();
    if (c.layer == 0 || c.layer == 3 || c.row == 0 || c.row == 3) {
      EXPECT_TRUE(c.contacts.empty()) << c.layer << "," << c.row << "," << c.col;
    }
  }
  EXPECT_EQ(contacts, f.contacts.size());
}

TEST(Blocks3D, EveryContactBelongsToExactlyOneCellTheOneHoldingItsContactPoint) {
  const Frame f = testing::fcc_frame({.cells = 4});
  validate(f);
  ASSERT_GT(f.contacts.size(), 1000u);
  for (const int k : {1, 2, 3, 5}) {
    const auto cells = split_into_blocks(f, k);
    ASSERT_EQ(cells.size(), static_cast<std::size_t>(k * k * k));
    std::vector<std::size_t> all;
    std::size_t grains = 0;
    for (const BlockCell& c : cells) {
      for (const std::size_t n : c.contacts) {
        all.push_back(n);
        EXPECT_TRUE(in_cell(c, k, contact_point_3d(f, f.contacts[n]))) << "k " << k << " contact " << n;
      }
      grains += c.grains.size();
    }
    std::sort(all.begin(), all.end());
    std::vector<std::size_t> expected(f.contacts.size());
    std::iota(expected.begin(), expected.end(), 0);
    EXPECT_EQ(all, expected) << "k " << k;
    EXPECT_GE(grains, f.particle_count) << "every grain is in some cell";
  }
}

// Each cell's distance equals the exact distance between the networks made of the contacts whose
// contact point lies in the cell by the face rule, chosen here on its own.
TEST(Blocks3D, CellDistancesAreTheExactDistancesOfTheCellsNetworks) {
  const Frame a = testing::fcc_frame({.cells = 3, .seed = 1}), b = testing::fcc_frame({.cells = 3, .seed = 2});
  validate(a), validate(b);
  constexpr int k = 2;
  const auto cells_a = split_into_blocks(a, k), cells_b = split_into_blocks(b, k);
  const auto cell_network = [](const Frame& f, const BlockCell& cell) {
    Frame out = f;
    out.label = "expected";
    out.contacts.clear();  // every grain stays: extra rattlers are zero-length points under floor
    for (const Contact& c : f.contacts)
      if (in_cell(cell, k, contact_point_3d(f, c))) out.contacts.push_back(c);
    return out;
  };
  expect_exact_cell_distances(a, b, cells_a, cells_b, cell_network, [](double expected, double, int dim) {
    if (dim == 0) {
      EXPECT_GT(expected, 0) << "two jitters differ in every octant";
    }
  });
}

}  // namespace
}  // namespace fnet
