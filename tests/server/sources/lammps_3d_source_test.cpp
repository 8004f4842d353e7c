// LAMMPS dumps of 3D runs, hand-written where the answer is known in closed form: spheres on a
// simple cubic lattice in a periodic box (ρ = π/6, Z = 6, every grain balanced) and on an FCC lattice
// between two layers of wall atoms (ρ = π/(3√2), Z = 10); forces split along the 3D line of centres,
// across periodic sides too; the run's dimension as lammps_dimension.hpp decides it, and the dumps
// that do not fit it named.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/server/sources/run_reading.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::sources::lammps3d {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using Vector = std::array<double, 3>;

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

struct Box {
  Vector lo{}, hi{};
  std::string flags = "pp pp pp";
};

// A snapshot of `item` (ATOMS or ENTRIES) with its rows as written.
std::string snapshot(const std::string& item, std::uint64_t step, const Box& box, const std::string& columns,
                     const std::vector<std::string>& rows) {
  std::string out = "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF " + item + "\n" +
                    std::to_string(rows.size()) + "\nITEM: BOX BOUNDS " + box.flags + "\n";
  for (std::size_t k = 0; k < 3; ++k) out += number(box.lo[k]) + " " + number(box.hi[k]) + "\n";
  out += "ITEM: " + item + " " + columns + "\n";
  for (const std::string& row : rows) out += row + "\n";
  return out;
}

struct Sphere {
  int id = 0, type = 1;
  Vector x{};
  double r = 0.5;
};

std::string atoms_dump(std::uint64_t step, const Box& box, const std::vector<Sphere>& spheres) {
  std::vector<std::string> rows;
  for (const Sphere& s : spheres)
    rows.push_back(std::to_string(s.id) + " " + std::to_string(s.type) + " " + number(s.x[0]) + " " + number(s.x[1]) +
                   " " + number(s.x[2]) + " " + number(s.r));
  return snapshot("ATOMS", step, box, "id type x y z radius", rows);
}

// A pair as the documented lines dump it: the ids, the normal force on i, the tangential force on i.
struct PairRow {
  int i = 0, j = 0;
  Vector normal{}, tangential{};
};

std::string pairs_dump(std::uint64_t step, const Box& box, const std::vector<PairRow>& pairs) {
  std::vector<std::string> rows;
  for (const PairRow& p : pairs) {
    std::string row = std::to_string(p.i);
    row += ' ';
    row += std::to_string(p.j);
    for (const Vector* v : {&p.normal, &p.tangential})
      for (const double c : *v) {
        row += ' ';
        row += number(c);
      }
    rows.push_back(row);
  }
  return snapshot("ENTRIES", step, box,
                  "c_fnet_pair[1] c_fnet_pair[2] c_fnet_force[1] c_fnet_force[2] c_fnet_force[3] c_fnet_force[4] "
                  "c_fnet_force[5] c_fnet_force[6]",
                  rows);
}

// The vector from b to a by the nearest image on the periodic axes.
Vector offset(const Vector& a, const Vector& b, const Box& box) {
  Vector d{};
  for (std::size_t k = 0; k < 3; ++k) {
    d[k] = a[k] - b[k];
    if (box.flags.substr(3 * k, 2) == "pp")
      d[k] -= (box.hi[k] - box.lo[k]) * std::round(d[k] / (box.hi[k] - box.lo[k]));
  }
  return d;
}

double length(const Vector& v) { return std::hypot(v[0], v[1], v[2]); }

Vector scaled(const Vector& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

// A unit vector perpendicular to n, turned about n by `angle`.
Vector perpendicular(const Vector& n, double angle) {
  const Vector helper = std::abs(n[0]) < 0.9 ? Vector{1, 0, 0} : Vector{0, 1, 0};
  Vector u{n[1] * helper[2] - n[2] * helper[1], n[2] * helper[0] - n[0] * helper[2],
           n[0] * helper[1] - n[1] * helper[0]};
  u = scaled(u, 1 / length(u));
  const Vector w{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  return {std::cos(angle) * u[0] + std::sin(angle) * w[0], std::cos(angle) * u[1] + std::sin(angle) * w[1],
          std::cos(angle) * u[2] + std::sin(angle) * w[2]};
}

// Every pair of spheres that touch (centres at most the sum of the radii apart, to rounding),
// each once, i < j.
std::vector<std::pair<std::size_t, std::size_t>> touching(const std::vector<Sphere>& spheres, const Box& box) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t a = 0; a < spheres.size(); ++a)
    for (std::size_t b = a + 1; b < spheres.size(); ++b)
      if (length(offset(spheres[a].x, spheres[b].x, box)) <= (spheres[a].r + spheres[b].r) * (1 + 1e-12))
        out.emplace_back(a, b);
  return out;
}

// The pairs of `touching` with a normal force fn(k) pushing the grains apart and a tangential one
// ft(k) turned by an angle that changes from pair to pair.
template <class Fn, class Ft>
std::vector<PairRow> pushing_pairs(const std::vector<Sphere>& spheres, const Box& box, Fn fn, Ft ft) {
  std::vector<PairRow> out;
  const auto pairs = touching(spheres, box);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Sphere &a = spheres[pairs[k].first], &b = spheres[pairs[k].second];
    const Vector d = offset(a.x, b.x, box);
    const Vector n = scaled(d, 1 / length(d));
    out.push_back({a.id, b.id, scaled(n, fn(k)), scaled(perpendicular(n, 0.7 * static_cast<double>(k)), ft(k))});
  }
  return out;
}

// 27 spheres of radius 1/2 on a simple cubic lattice of spacing 1, in a periodic box of side 3:
// each touches six, three of them across a periodic side.
const Box kCubicBox{{0, 0, 0}, {3, 3, 3}, "pp pp pp"};

std::vector<Sphere> simple_cubic() {
  std::vector<Sphere> out;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) out.push_back({1 + i + 3 * j + 9 * k, 1, {i + 0.5, j + 0.5, k + 0.5}});
  return out;
}

TEST(Lammps3d, SimpleCubicInAPeriodicBox) {
  testing::TempDir dir;
  const std::vector<Sphere> spheres = simple_cubic();
  // Step 1: every contact pushes with 1, no tangential force: every grain balanced. Step 2: each
  // contact its own normal and tangential force.
  const auto uniform = pushing_pairs(
      spheres, kCubicBox, [](std::size_t) { return 1.0; }, [](std::size_t) { return 0.0; });
  const auto fn = [](std::size_t k) { return 0.5 + 0.01 * static_cast<double>(k); };
  const auto ft = [](std::size_t k) { return 0.003 * static_cast<double>(k % 7); };
  const auto varied = pushing_pairs(spheres, kCubicBox, fn, ft);
  ASSERT_EQ(uniform.size(), 81u);
  dir.write("atoms.txt", atoms_dump(1, kCubicBox, spheres) + atoms_dump(2, kCubicBox, spheres));
  dir.write("pairs.txt", pairs_dump(1, kCubicBox, uniform) + pairs_dump(2, kCubicBox, varied));
  dir.write("balanced.txt", pairs_dump(1, kCubicBox, uniform));
  dir.write("atoms1.txt", atoms_dump(1, kCubicBox, spheres));
  const auto source =
      testing::open_run_source(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt"});
  const auto config = nlohmann::json::parse(source->announcement().config_json);
  EXPECT_EQ(config["source"]["dimension"], 3);
  EXPECT_EQ(config["source"]["rho"], "periodic box");
  std::vector<RunFrame> frames;
  while (auto f = source->next()) frames.push_back(std::move(*f));
  ASSERT_EQ(frames.size(), 2u);
  for (const RunFrame& f : frames) {
    EXPECT_EQ(f.frame.dimension, 3);
    EXPECT_NO_THROW(validate(f.frame));
    EXPECT_NEAR(f.header.rho, std::numbers::pi / 6, 1e-15);
    EXPECT_DOUBLE_EQ(f.header.z, 6.0);
    ASSERT_EQ(f.frame.particles.size(), 27u);
    EXPECT_EQ(f.frame.particles[26].z, 2.5);
    EXPECT_EQ(f.frame.particles[9].z, 1.5);
  }
  // The split along the line of centres, which for a third of the pairs crosses a periodic side.
  ASSERT_EQ(frames[1].frame.contacts.size(), varied.size());
  for (std::size_t k = 0; k < varied.size(); ++k) {
    EXPECT_NEAR(frames[1].frame.contacts[k].fn, fn(k), 1e-14) << k;
    EXPECT_NEAR(frames[1].frame.contacts[k].ft, ft(k), 1e-14) << k;
  }
  // The whole force on i given as one vector (fx, fy, fz): the same split.
  std::vector<std::string> totals;
  for (const PairRow& p : varied)
    totals.push_back(std::to_string(p.i) + " " + std::to_string(p.j) + " " + number(p.normal[0] + p.tangential[0]) +
                     " " + number(p.normal[1] + p.tangential[1]) + " " + number(p.normal[2] + p.tangential[2]));
  dir.write("atoms2.txt", atoms_dump(2, kCubicBox, spheres));
  dir.write("totals.txt", snapshot("ENTRIES", 2, kCubicBox, "i j fx fy fz", totals));
  const auto total = testing::read_run_frames(dir.path(), {"--lammps-atoms", "@atoms2.txt", "--lammps-pairs",
                                                           "@totals.txt", "--columns", "i=i,j=j,fx=fx,fy=fy,fz=fz"});
  for (std::size_t k = 0; k < varied.size(); ++k) {
    EXPECT_NEAR(total[0].frame.contacts[k].fn, fn(k), 1e-14) << k;
    EXPECT_NEAR(total[0].frame.contacts[k].ft, ft(k), 1e-14) << k;
  }
  // Newton's first law in 3D: the uniform frame holds it to rounding; with one contact along z
  // pushing harder, its two grains are out of balance, along z alone.
  EXPECT_EQ(testing::read_run_frames(dir.path(), {"--lammps-atoms", "@atoms1.txt", "--lammps-pairs", "@balanced.txt",
                                                  "--check-balance", "1e-12"})
                .size(),
            1u);
  std::vector<PairRow> harder = uniform;
  const auto along_z = std::find_if(harder.begin(), harder.end(), [](const PairRow& p) { return p.normal[2] != 0; });
  ASSERT_NE(along_z, harder.end());
  along_z->normal = scaled(along_z->normal, 1.5);
  dir.write("harder.txt", pairs_dump(1, kCubicBox, harder));
  EXPECT_THAT(
      testing::run_error(dir.path(),
                         {"--lammps-atoms", "@atoms1.txt", "--lammps-pairs", "@harder.txt", "--check-balance", "0.01"}),
      AllOf(HasSubstr("2 of 27 grains out of force balance"), HasSubstr(" " + std::to_string(along_z->i) + " at "),
            HasSubstr(" " + std::to_string(along_z->j) + " at ")));
}

// Followed while written, a run's dimension is its first frame's (or --dimension's): LAMMPS writes
// its log behind the dumps, so the log's dimension command is not waited for.
TEST(Lammps3d, AFollowedRunsDimensionIsItsFirstFrames) {
  testing::TempDir dir;
  const std::vector<Sphere> spheres = simple_cubic();
  const auto contacts = pushing_pairs(
      spheres, kCubicBox, [](std::size_t) { return 1.0; }, [](std::size_t) { return 0.0; });
  dir.write("atoms.txt", atoms_dump(1, kCubicBox, spheres) + atoms_dump(2, kCubicBox, spheres));
  dir.write("pairs.txt", pairs_dump(1, kCubicBox, contacts) + pairs_dump(2, kCubicBox, contacts));
  dir.write("log.lammps", "dimension 2\n");
  const auto frames =
      testing::read_run_frames(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--follow",
                                            "--idle-timeout", "0.2", "--lammps-log", "@log.lammps"});
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].frame.dimension, 3);
  EXPECT_NEAR(frames[1].header.rho, std::numbers::pi / 6, 1e-15);
}

// FCC of spheres of diameter 1 (cube side a = √2), 2 × 2 × 2 cells periodic in x and y, between a
// layer of wall atoms under the grains and one over them whose inner surfaces are a/4 from the
// outer layers of grains: the region is then 2a × 2a × 2a, as the periodic crystal's.
TEST(Lammps3d, FaceCentredCubicBetweenWallAtoms) {
  testing::TempDir dir;
  const double a = std::numbers::sqrt2;
  Box box{{0, 0, -2}, {2 * a, 2 * a, 2 * a + 2}, "pp pp ff"};
  std::vector<Sphere> spheres;
  const std::array<Vector, 4> basis{{{0, 0, 0}, {a / 2, a / 2, 0}, {a / 2, 0, a / 2}, {0, a / 2, a / 2}}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        for (const Vector& b : basis)
          spheres.push_back({static_cast<int>(spheres.size()) + 1, 1, {i * a + b[0], j * a + b[1], k * a + b[2]}, 0.5});
  const std::size_t grains = spheres.size();
  const auto contacts = pushing_pairs(
      spheres, box, [](std::size_t) { return 1.0; }, [](std::size_t) { return 0.1; });
  // 12 neighbours each, but for the 4 missing over the top layer and under the bottom one.
  ASSERT_EQ(contacts.size(), (grains * 12 - 2 * 8 * 4) / 2);
  // Wall atoms of radius 1/2 over the grains' footprint, their surfaces at z = -a/4 and 7a/4; one
  // more beside the grains (x past theirs), lower than the top wall: not level with the grains, not
  // a bound of their region.
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      for (const double z : {-a / 4 - 0.5, 7 * a / 4 + 0.5})
        spheres.push_back({static_cast<int>(spheres.size()) + 1, 2, {0.7 * i, 0.7 * j, z}, 0.5});
  spheres.push_back({static_cast<int>(spheres.size()) + 1, 2, {2.5, 1.0, 1.5 * a + 0.3}, 0.5});
  dir.write("atoms.txt", atoms_dump(0, box, spheres));
  dir.write("pairs.txt", pairs_dump(0, box, contacts));
  const auto source = testing::open_run_source(
      dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--wall-types", "2"});
  EXPECT_EQ(nlohmann::json::parse(source->announcement().config_json)["source"]["rho"], "wall atoms");
  const auto frame = source->next();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->frame.dimension, 3);
  EXPECT_EQ(frame->frame.particle_count, grains);
  EXPECT_NEAR(frame->header.rho, std::numbers::pi / (3 * std::numbers::sqrt2), 1e-14);
  EXPECT_DOUBLE_EQ(frame->header.z, 10.0);
  for (const Contact& c : frame->frame.contacts) {
    EXPECT_NEAR(c.fn, 1.0, 1e-14);
    EXPECT_NEAR(c.ft, 0.1, 1e-14);
  }
}

// A sphere on the plane of a fix wall/gran ... contacts: the normal is the line from the contact
// point to the centre in 3D, here out of the xy plane.
TEST(Lammps3d, FixWallContactSplitIn3d) {
  testing::TempDir dir;
  const Box box{{-2, -2, 0}, {2, 2, 3}, "pp pp ff"};
  const std::string columns = "id type x y z radius f_w[1] f_w[2] f_w[3] f_w[4] f_w[5] f_w[6] f_w[7]";
  dir.write("atoms.txt", snapshot("ATOMS", 0, box, columns,
                                  {"1 1 0.25 0 1 0.5 1 0.3 0 2 0.25 0 0.5", "2 1 1.25 0 2 0.5 0 0 0 0 0 0 0"}));
  dir.write("pairs.txt", pairs_dump(0, box, {}));
  const auto frames = testing::read_run_frames(
      dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--columns", "wall=w"});
  ASSERT_EQ(frames[0].wall_contacts.size(), 1u);
  EXPECT_EQ(frames[0].wall_contacts[0].particle, 0u);
  EXPECT_DOUBLE_EQ(frames[0].wall_contacts[0].fn, 2.0);
  EXPECT_DOUBLE_EQ(frames[0].wall_contacts[0].ft, 0.3);
  // ρ over the box (no wall atoms): two spheres of radius 1/2 in 4 × 4 × 3.
  EXPECT_DOUBLE_EQ(frames[0].header.rho, 2 * std::numbers::pi / 6 / 48);
}

// The dimension: a z column of one value is a 2D run's (its grains at z = 0, ρ an area fraction);
// one that varies, a 3D run's; --dimension and the log's dimension command decide before the dumps.
TEST(Lammps3d, TheRunsDimension) {
  testing::TempDir dir;
  const Box box{{0, 0, -0.5}, {3, 3, 0.5}, "pp pp pp"};
  std::vector<Sphere> flat;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) flat.push_back({1 + i + 3 * j, 1, {i + 0.5, j + 0.5, 0.25}});
  std::vector<Sphere> lifted = flat;
  lifted[4].x[2] = 0.3;
  const auto flat_pairs = pushing_pairs(
      flat, box, [](std::size_t) { return 1.0; }, [](std::size_t) { return 0.0; });
  dir.write("flat.txt", atoms_dump(0, box, flat));
  dir.write("run.txt", atoms_dump(0, box, flat) + atoms_dump(1, box, lifted));
  dir.write("pairs.txt", pairs_dump(0, box, flat_pairs) + pairs_dump(1, box, flat_pairs));
  dir.write("pairs0.txt", pairs_dump(0, box, flat_pairs));
  const std::vector<std::string> base{"--lammps-atoms", "@flat.txt", "--lammps-pairs", "@pairs0.txt"};
  const auto plain = testing::read_run_frames(dir.path(), base);
  EXPECT_EQ(plain[0].frame.dimension, 2);
  EXPECT_EQ(plain[0].frame.particles[4].z, 0.0) << "a 2D frame's grains lie at z = 0";
  EXPECT_DOUBLE_EQ(plain[0].header.rho, 9 * std::numbers::pi / 4 / 9);
  EXPECT_DOUBLE_EQ(plain[0].header.z, 4.0);
  // The same atoms read as a 3D run: spheres in the 3 × 3 × 1 box.
  std::vector<std::string> three = base;
  three.insert(three.end(), {"--dimension", "3"});
  const auto as_3d = testing::read_run_frames(dir.path(), three);
  EXPECT_EQ(as_3d[0].frame.dimension, 3);
  EXPECT_EQ(as_3d[0].frame.particles[4].z, 0.25);
  EXPECT_DOUBLE_EQ(as_3d[0].header.rho, 9 * std::numbers::pi / 6 / 9);
  // A run whose first frame is flat is 2D, unless told: a later frame off the plane is named.
  const std::vector<std::string> run{"--lammps-atoms", "@run.txt", "--lammps-pairs", "@pairs.txt"};
  EXPECT_THAT(
      testing::run_error(dir.path(), run),
      AllOf(HasSubstr((dir.path() / "run.txt").string() + ":32:"), HasSubstr("atoms at different z in a 2D run"),
            HasSubstr("the z of the first frame, " + (dir.path() / "run.txt").string() + ":1"),
            HasSubstr("--dimension 3")));
  std::vector<std::string> told = run;
  told.insert(told.end(), {"--dimension", "3"});
  EXPECT_EQ(testing::read_run_frames(dir.path(), told)[1].frame.particles[4].z, 0.3);
  // The log's dimension command (echoed, then with its variable substituted).
  dir.write("log.lammps", "LAMMPS (29 Sep 2021 - Update 2)\nvariable d equal 3\ndimension ${d}\ndimension 3\n");
  std::vector<std::string> logged = run;
  logged.insert(logged.end(), {"--lammps-log", "@log.lammps"});
  EXPECT_EQ(testing::read_run_frames(dir.path(), logged)[1].frame.dimension, 3);
  dir.write("log2.lammps", "dimension 2 # a plane\n");
  EXPECT_THAT(testing::run_error(dir.path(), {"--lammps-atoms", "@run.txt", "--lammps-pairs", "@pairs.txt",
                                              "--lammps-log", "@log2.lammps"}),
              AllOf(HasSubstr("atoms at different z in a 2D run"), HasSubstr("log2.lammps:1")));
  // A 3D run needs a z column.
  dir.write("noz.txt", snapshot("ATOMS", 0, box, "id x y radius", {"1 0.5 0.5 0.5", "2 1.5 0.5 0.5"}));
  EXPECT_THAT(
      testing::run_error(dir.path(),
                         {"--lammps-atoms", "@noz.txt", "--lammps-pairs", "@pairs0.txt", "--dimension", "3"}),
      AllOf(HasSubstr((dir.path() / "noz.txt").string() + ":9:"), HasSubstr("no column z"), HasSubstr("--dimension")));
  std::vector<std::string> four = base;
  four.insert(four.end(), {"--dimension", "4"});
  EXPECT_THAT(testing::run_error(dir.path(), four), HasSubstr("--dimension: \"4\" is neither 2 nor 3"));
}

}  // namespace
}  // namespace fnet::sources::lammps3d
