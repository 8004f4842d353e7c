// The contacts CSV's second form, i,j,fx,fy[,fz]: force vectors split along the line of centres, as
// experiments (photoelastic disks and spheres) and other codes report them, in 2D and in 3D (a
// particles table with z). A frame written both ways has the same diagrams; proto/frames.md's
// examples read as they say.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/codec/frame_csv.hpp"
#include "common/topology/contact_force.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"
#include "tests/common/codec/csv_error.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

using fnet::testing::TempDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

using fnet::testing::csv_error;

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// A photoelastic-like frame: a bidisperse packing of disks (radii 0.5 and 0.6, as the two sizes of
// an experiment's disks) on a jittered triangular lattice, each neighbouring pair in contact with
// probability 0.7 (missing contacts leave loops of four or more grains, so PD1 is not empty), a
// normal force drawn from an exponential law and a tangential one up to 0.5 of it, a quarter of
// the contacts purely normal (ft = 0, as α = 0 in a photoelastic fit).
Frame photoelastic_like_frame() {
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::exponential_distribution<double> exponential(1.0);
  constexpr int kSide = 24;
  Frame frame;
  frame.label = "photoelastic-like";
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col)
      frame.particles.push_back({1.1 * (col + 0.5 * (row % 2)) + 0.05 * (unit(random) - 0.5),
                                 1.1 * std::sqrt(3.0) / 2 * row + 0.05 * (unit(random) - 0.5),
                                 unit(random) < 0.5 ? 0.5 : 0.6});
  frame.particle_count = frame.particles.size();
  const auto index = [&](int row, int col) { return static_cast<std::int64_t>(row * kSide + col); };
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) {
      // The neighbours to the right, up-right and up-left on the lattice (odd rows shifted right).
      const int shift = row % 2;
      const std::vector<std::pair<int, int>> neighbours{
          {row, col + 1}, {row + 1, col + shift}, {row + 1, col + shift - 1}};
      for (const auto& [r, c] : neighbours) {
        if (r >= kSide || c < 0 || c >= kSide || unit(random) > 0.7) continue;
        const double fn = 0.05 + exponential(random);
        const double ft = unit(random) < 0.25 ? 0.0 : 0.5 * fn * unit(random);
        frame.contacts.push_back({index(row, col), index(r, c), fn, ft});
      }
    }
  return frame;
}

// Writes the particles table and the contacts, as magnitudes or as the force on grain i: its
// normal part along x_i - x_j and its tangential part on either side, at random.
std::string particles_csv(const Frame& frame) {
  std::string out = "id,x,y,r\n";
  for (std::size_t k = 0; k < frame.particles.size(); ++k) {
    const Particle& p = frame.particles[k];
    out += std::to_string(k) + "," + number(p.x) + "," + number(p.y) + "," + number(p.r) + "\n";
  }
  return out;
}

std::string magnitudes_csv(const Frame& frame) {
  std::string out = "i,j,fn,ft\n";
  for (const Contact& c : frame.contacts)
    out += std::to_string(c.i) + "," + std::to_string(c.j) + "," + number(c.fn) + "," + number(c.ft) + "\n";
  return out;
}

std::string vectors_csv(const Frame& frame) {
  std::mt19937_64 random(5);
  std::string out = "i,j,fx,fy\n";
  for (const Contact& c : frame.contacts) {
    const Particle& a = frame.particles[static_cast<std::size_t>(c.i)];
    const Particle& b = frame.particles[static_cast<std::size_t>(c.j)];
    const double length = std::hypot(a.x - b.x, a.y - b.y);
    const double nx = (a.x - b.x) / length, ny = (a.y - b.y) / length;
    const double side = random() % 2 ? 1.0 : -1.0;
    const double fx = c.fn * nx - side * c.ft * ny, fy = c.fn * ny + side * c.ft * nx;
    out += std::to_string(c.i) + "," + std::to_string(c.j) + "," + number(fx) + "," + number(fy) + "\n";
  }
  return out;
}

void expect_close(const Diagram& got, const Diagram& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_NEAR(got[k].birth, want[k].birth, 1e-12) << what << " point " << k;
    EXPECT_NEAR(got[k].death, want[k].death, 1e-12) << what << " point " << k;
  }
}

// The frame drawn as `frame`, written as its particles table and its contacts as vectors, read back:
// it holds the drawn fn and ft (a purely normal force with ft exactly 0, more than `purely_normal`
// of them), and has the diagrams of the same frame written as magnitudes, in both networks.
Frame expect_read_as_drawn(const Frame& frame, const std::string& particles_text, const std::string& vectors_text,
                           std::size_t purely_normal) {
  TempDir dir;
  const auto particles = dir.write("p.csv", particles_text);
  const Frame magnitudes = read_frame_csv(dir.write("magnitudes.csv", magnitudes_csv(frame)), particles);
  const Frame vectors = read_frame_csv(dir.write("vectors.csv", vectors_text), particles);
  EXPECT_EQ(magnitudes.dimension, vectors.dimension);
  EXPECT_EQ(vectors.contacts.size(), frame.contacts.size());
  if (vectors.contacts.size() != frame.contacts.size()) return vectors;
  std::size_t zero = 0;
  for (std::size_t k = 0; k < frame.contacts.size(); ++k) {
    EXPECT_NEAR(vectors.contacts[k].fn, frame.contacts[k].fn, 2e-14 * frame.contacts[k].fn) << k;
    EXPECT_NEAR(vectors.contacts[k].ft, frame.contacts[k].ft, 2e-14 * frame.contacts[k].fn) << k;
    if (frame.contacts[k].ft == 0) {
      ++zero;
      EXPECT_EQ(vectors.contacts[k].ft, 0.0) << "a purely normal force has no tangential part, not rounding: " << k;
    }
  }
  EXPECT_GT(zero, purely_normal);
  for (const ForceKind kind : {ForceKind::normal, ForceKind::tangential}) {
    const FrameDiagrams want = compute_persistence(build_network(magnitudes, kind));
    const FrameDiagrams got = compute_persistence(build_network(vectors, kind));
    EXPECT_FALSE(want.pd1.empty()) << "the frame must have loops to compare";
    EXPECT_GT(want.triangles, 0u);
    EXPECT_EQ(got.edges, want.edges);
    EXPECT_EQ(got.triangles, want.triangles);
    expect_close(got.pd0, want.pd0, kind == ForceKind::normal ? "normal pd0" : "tangential pd0");
    expect_close(got.pd1, want.pd1, kind == ForceKind::normal ? "normal pd1" : "tangential pd1");
  }
  return vectors;
}

TEST(FrameCsvVectors, PhotoelasticLikeFrameGivenAsVectorsHasTheDiagramsOfItsMagnitudes) {
  const Frame frame = photoelastic_like_frame();
  EXPECT_EQ(expect_read_as_drawn(frame, particles_csv(frame), vectors_csv(frame), 50).dimension, 2);
}

// Its 3D counterpart: spheres (radii 0.5 and 0.6) on a jittered simple cubic lattice, each pair of
// lattice or face-diagonal neighbours in contact with probability 0.5 (the diagonals close
// triangles, the missing contacts leave loops), the forces drawn as above; the tangential force's
// direction in the plane normal to the line of centres is drawn too.
Frame photoelastic_like_frame_3d() {
  std::mt19937_64 random(33);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::exponential_distribution<double> exponential(1.0);
  constexpr int kSide = 8;
  Frame frame;
  frame.label = "photoelastic-like 3D";
  frame.dimension = 3;
  const auto jitter = [&] { return 0.05 * (unit(random) - 0.5); };
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i)
        frame.particles.push_back(
            {1.1 * i + jitter(), 1.1 * j + jitter(), unit(random) < 0.5 ? 0.5 : 0.6, 1.1 * k + jitter()});
  frame.particle_count = frame.particles.size();
  const auto index = [&](int i, int j, int k) { return static_cast<std::int64_t>((k * kSide + j) * kSide + i); };
  const std::vector<std::array<int, 3>> steps{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}};
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i)
        for (const auto& s : steps) {
          const int a = i + s[0], b = j + s[1], c = k + s[2];
          if (a >= kSide || b >= kSide || c >= kSide || unit(random) > 0.5) continue;
          const double fn = 0.05 + exponential(random);
          const double ft = unit(random) < 0.25 ? 0.0 : 0.5 * fn * unit(random);
          frame.contacts.push_back({index(i, j, k), index(a, b, c), fn, ft});
        }
  return frame;
}

std::string particles_csv_3d(const Frame& frame) {
  std::string out = "id,x,y,r,z\n";
  for (std::size_t k = 0; k < frame.particles.size(); ++k) {
    const Particle& p = frame.particles[k];
    out += std::to_string(k) + "," + number(p.x) + "," + number(p.y) + "," + number(p.r) + "," + number(p.z) + "\n";
  }
  return out;
}

// The force on grain i as fn n + ft t, n along x_i - x_j and t a unit vector normal to n at an
// angle drawn from [0, 2π) about it.
std::string vectors_csv_3d(const Frame& frame) {
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  std::string out = "fz,i,j,fx,fy\n";  // columns in any order
  for (const Contact& c : frame.contacts) {
    const Particle& a = frame.particles[static_cast<std::size_t>(c.i)];
    const Particle& b = frame.particles[static_cast<std::size_t>(c.j)];
    std::array<double, 3> n{a.x - b.x, a.y - b.y, a.z - b.z};
    const double length = std::hypot(n[0], n[1], n[2]);
    for (double& v : n) v /= length;
    // u and w: an orthonormal basis of the plane normal to n.
    std::array<double, 3> u{n[1], -n[0], 0.0};
    if (std::hypot(u[0], u[1]) < 0.5) u = {0.0, n[2], -n[1]};
    const double u_length = std::hypot(u[0], u[1], u[2]);
    for (double& v : u) v /= u_length;
    const std::array<double, 3> w{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    const double theta = angle(random);
    std::array<double, 3> f{};
    for (std::size_t k = 0; k < 3; ++k) f[k] = c.fn * n[k] + c.ft * (std::cos(theta) * u[k] + std::sin(theta) * w[k]);
    out += number(f[2]) + "," + std::to_string(c.i) + "," + std::to_string(c.j) + "," + number(f[0]) + "," +
           number(f[1]) + "\n";
  }
  return out;
}

TEST(FrameCsvVectors, PhotoelasticLike3dFrameGivenAsVectorsHasTheDiagramsOfItsMagnitudes) {
  const Frame frame = photoelastic_like_frame_3d();
  const Frame vectors = expect_read_as_drawn(frame, particles_csv_3d(frame), vectors_csv_3d(frame), 100);
  EXPECT_EQ(vectors.dimension, 3);
  EXPECT_NO_THROW(validate(vectors));
  EXPECT_EQ(vectors.particles[100].z, frame.particles[100].z);
}

// By hand: grain 1 at (1, 2, 2) and grain 0 at the origin, |x_1 - x_0| = 3, n = (1, 2, 2)/3; the
// force (3, 0, 3) on grain 1 has F·n = (3 + 0 + 6)/3 = 3 and F - 3n = (2, -2, 1), of length 3.
// Without fz the same row has F·n = 1 and F - n = (8/3, -2/3, -2/3), of length 2√2.
TEST(FrameCsvVectors, ASplitIn3dByHand) {
  TempDir dir;
  const auto particles = dir.write("p.csv", "id,x,y,z,r\n0,0,0,0,1.5\n1,1,2,2,1.5\n");
  const Frame f = read_frame_csv(dir.write("c.csv", "i,j,fx,fy,fz\n1,0,3,0,3\n"), particles);
  EXPECT_EQ(f.dimension, 3);
  ASSERT_EQ(f.contacts.size(), 1u);
  EXPECT_NEAR(f.contacts[0].fn, 3.0, 4e-15);
  EXPECT_NEAR(f.contacts[0].ft, 3.0, 4e-15);
  const Frame planar_force = read_frame_csv(dir.write("c2.csv", "i,j,fx,fy\n1,0,3,0\n"), particles);
  EXPECT_NEAR(planar_force.contacts[0].fn, 1.0, 4e-15);
  EXPECT_NEAR(planar_force.contacts[0].ft, 2 * std::numbers::sqrt2, 4e-15);
  // The same grains without z: a 2D frame, whose line of centres lies in the plane.
  const Frame flat = read_frame_csv(dir.write("c3.csv", "i,j,fx,fy\n1,0,3,4\n"),
                                    dir.write("p2.csv", "id,x,y,r\n0,0,0,1.5\n1,3,4,1.5\n"));
  EXPECT_EQ(flat.dimension, 2);
  EXPECT_EQ(flat.particles[1].z, 0.0);
  EXPECT_NEAR(flat.contacts[0].fn, 5.0, 4e-15);
  EXPECT_EQ(flat.contacts[0].ft, 0.0);
}

TEST(FrameCsvVectors, AZColumnThatIsNotANumberIsNamed) {
  TempDir dir;
  const auto particles = dir.write("p.csv", "id,x,y,r,z\n0,0,0,0.5,0\n1,1,0,0.5,up\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(particles); }),
              AllOf(HasSubstr(particles.string() + ":3:"), HasSubstr("column 'z'")));
  const auto contacts = dir.write("c.csv", "i,j,fx,fy,fz\n0,1,1,0,\n");
  EXPECT_THAT(csv_error([&] { read_frame_csv(contacts, dir.write("p2.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n")); }),
              AllOf(HasSubstr(contacts.string() + ":2:"), HasSubstr("column 'fz'")));
}

// The blocks of proto/frames.md fenced as ```LANG (the word after the backticks, with its tag).
std::vector<std::string> page_blocks(const std::string& lang) {
  std::ifstream in(std::string(FNET_SOURCE_DIR) + "/proto/frames.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  std::vector<std::string> blocks;
  const std::regex block("```" + lang + "\n([^`]*)```");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), block); it != std::sregex_iterator(); ++it)
    blocks.push_back((*it)[1].str());
  return blocks;
}

// proto/frames.md's examples, taken from the page: the csv blocks, particles then contacts.
TEST(FrameCsvVectors, TheDocumentsExampleReadsAsItSays) {
  const std::vector<std::string> blocks = page_blocks("csv");
  ASSERT_EQ(blocks.size(), 2u);
  TempDir dir;
  const Frame f = read_frame_csv(dir.write("c.csv", blocks[1]), dir.write("p.csv", blocks[0]));
  EXPECT_EQ(f.dimension, 2);
  ASSERT_EQ(f.contacts.size(), 2u);
  EXPECT_EQ(f.contacts[0].fn, 2.0);
  EXPECT_EQ(f.contacts[0].ft, 0.0);
  EXPECT_EQ(f.contacts[1].fn, 1.0);
  EXPECT_EQ(f.contacts[1].ft, 0.5);
}

TEST(FrameCsvVectors, TheDocuments3dExampleReadsAsItSays) {
  const std::vector<std::string> blocks = page_blocks("csv 3d");
  ASSERT_EQ(blocks.size(), 2u);
  TempDir dir;
  const Frame f = read_frame_csv(dir.write("c.csv", blocks[1]), dir.write("p.csv", blocks[0]));
  EXPECT_EQ(f.dimension, 3);
  ASSERT_EQ(f.contacts.size(), 1u);
  EXPECT_NEAR(f.contacts[0].fn, 3.0, 4e-15);
  EXPECT_NEAR(f.contacts[0].ft, 3.0, 4e-15);
}

TEST(FrameCsvVectors, SplitIsAlongTheLineOfCentresFromJToI) {
  // The force on i pushing it away from j is compressive (fn > 0) whichever way the pair lies.
  EXPECT_EQ(split_contact_force({3, 4, 0}, {3, 4, 0}).fn, 5.0);
  EXPECT_EQ(split_contact_force({-3, -4, 0}, {-3, -4, 0}).fn, 5.0);
  EXPECT_EQ(split_contact_force({3, 4, 0}, {-3, -4, 0}).fn, -5.0);
  const ContactForceParts sheared = split_contact_force({0, 2, 0}, {1.5, 2, 0});
  EXPECT_EQ(sheared.fn, 2.0);
  EXPECT_EQ(sheared.ft, 1.5);
  const ContactForceParts pure = split_contact_force({1, 1, 0}, {std::sqrt(0.5), std::sqrt(0.5), 0});
  EXPECT_NEAR(pure.fn, 1.0, 1e-15);
  EXPECT_EQ(pure.ft, 0.0) << "rounding of the split is not a tangential force";
  // In 3D: the line of centres (1, 2, 2)/3 and the force (3, 0, 3): F·n = 3, F - 3n = (2, -2, 1).
  const ContactForceParts spatial = split_contact_force({1, 2, 2}, {3, 0, 3});
  EXPECT_NEAR(spatial.fn, 3.0, 4e-15);
  EXPECT_NEAR(spatial.ft, 3.0, 4e-15);
  const ContactForceParts diagonal = split_contact_force({-1, -1, -1}, {2, 2, 2});
  EXPECT_NEAR(diagonal.fn, -2 * std::sqrt(3.0), 1e-14);
  EXPECT_EQ(diagonal.ft, 0.0) << "rounding of the split is not a tangential force, in 3D too";
  const ContactForceParts together = split_contact_force({0, 0, 0}, {3, 4, 0});
  EXPECT_EQ(together.fn, 0.0);
  EXPECT_EQ(together.ft, 5.0);
}

TEST(FrameCsvVectors, VectorsWithoutPositionsAreRefusedNamingTheFile) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fx,fy\n0,1,1,0\n");
  EXPECT_THAT(csv_error([&] { read_frame_csv(contacts, std::nullopt); }),
              AllOf(HasSubstr(contacts.string()), HasSubstr("fx,fy"), HasSubstr("particles")));
  EXPECT_THAT(csv_error([&] { read_contacts_csv(contacts); }), AllOf(HasSubstr(contacts.string()), HasSubstr("fx,fy")));
  const auto particles = dir.write("p.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n");
  const auto beyond = dir.write("c2.csv", "i,j,fx,fy\n0,1,1,0\n1,2,1,0\n");
  EXPECT_THAT(csv_error([&] { read_frame_csv(beyond, particles); }),
              AllOf(HasSubstr(beyond.string() + ":3:"), HasSubstr("particle index 2")));
}

TEST(FrameCsvVectors, AHeaderWithNeitherFormNamesBoth) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fx,ft\n0,1,1,0\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(contacts); }),
              AllOf(HasSubstr(contacts.string() + ":1:"), HasSubstr("'fn'"), HasSubstr("i,j,fn,ft or i,j,fx,fy")));
}

TEST(FrameCsvVectors, MagnitudesWinWhenAFileHasBothForms) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fx,fy,fn,ft\n0,1,9,9,1.5,0.25\n");
  const Frame f = read_frame_csv(contacts, std::nullopt);
  ASSERT_EQ(f.contacts.size(), 1u);
  EXPECT_EQ(f.contacts[0].fn, 1.5);
  EXPECT_EQ(f.contacts[0].ft, 0.25);
}

}  // namespace
}  // namespace fnet
