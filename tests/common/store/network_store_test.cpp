// The analysis store keeps each accepted frame's force network (since fnet-store-2; with its
// dimension and z since fnet-store-3), written with the frame's commit and read back one frame at a
// time; stores of the earlier schemas still load, those of the first without networks.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_io.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;
const fs::path kStoreV1 = fs::path(FNET_TEST_DATA) / "store-v1" / "legacy-v1.h5";
const fs::path kStoreV2 = fs::path(FNET_TEST_DATA) / "store-v2" / "legacy-v2.h5";

AnalyzedFrame with_network(std::uint32_t index, Frame network) {
  AnalyzedFrame f;
  f.header = {"nets", index, 100ull * index, 0.5, 0.8, 3.5};
  f.dimension = network.dimension;
  f.diagrams = analyze_frame(network);
  if (index > 0) f.previous = index - 1;
  f.network = std::make_shared<const Frame>(std::move(network));
  return f;
}

void expect_same_network(const Frame& got, const Frame& want) {
  EXPECT_EQ(got.particle_count, want.particle_count);
  EXPECT_EQ(got.dimension, want.dimension);
  ASSERT_EQ(got.particles.size(), want.particles.size());
  for (std::size_t k = 0; k < got.particles.size(); ++k) {
    EXPECT_EQ(got.particles[k].x, want.particles[k].x);
    EXPECT_EQ(got.particles[k].y, want.particles[k].y);
    EXPECT_EQ(got.particles[k].z, want.particles[k].z);
    EXPECT_EQ(got.particles[k].r, want.particles[k].r);
  }
  ASSERT_EQ(got.contacts.size(), want.contacts.size());
  for (std::size_t k = 0; k < got.contacts.size(); ++k) {
    EXPECT_EQ(got.contacts[k].i, want.contacts[k].i);
    EXPECT_EQ(got.contacts[k].j, want.contacts[k].j);
    EXPECT_EQ(got.contacts[k].fn, want.contacts[k].fn);
    EXPECT_EQ(got.contacts[k].ft, want.contacts[k].ft);
  }
}

// A 3D frame: the LAMMPS frame's disks lifted to different heights.
Frame lifted(Frame f) {
  f.dimension = 3;
  for (std::size_t k = 0; k < f.particles.size(); ++k) f.particles[k].z = 0.37 * static_cast<double>(k % 11) - 1.5;
  return f;
}

TEST(NetworkStore, EveryFrameKeepsItsNetworkWhileWrittenAfterwardsAndWhenContinued) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "nets.h5";
  const Frame a = testing::lammps_frame(3), b = lifted(testing::lammps_frame(10));
  {
    StoreWriter w(path, "nets");
    w.append(with_network(4, a));
    AnalyzedFrame without = with_network(5, a);
    without.network.reset();
    w.append(without);
    w.append(with_network(7, b));
    expect_same_network(*w.network(4), a);  // through the writer's open file
    expect_same_network(*w.network(7), b);
    EXPECT_FALSE(w.network(5).has_value());
    EXPECT_THROW(w.network(6), h5::Error);
  }
  for (int continued = 0; continued < 2; ++continued) {
    SCOPED_TRACE(continued);
    const StoredRun s = read_store(path);
    EXPECT_EQ(s.schema, kStoreSchema);
    EXPECT_EQ(s.has_network, (std::vector<bool>{true, false, true}));
    for (const AnalyzedFrame& f : s.frames) EXPECT_FALSE(f.network);  // read on demand only
    const auto got = read_network(path, 7);
    ASSERT_TRUE(got.has_value());
    expect_same_network(*got, b);
    EXPECT_EQ(got->label, "run nets frame 7");
    EXPECT_FALSE(read_network(path, 5).has_value());
    EXPECT_THROW(read_network(path, 6), h5::Error);
    StoreWriter again(path, "nets");  // copies every record, networks included, into a fresh file
    expect_same_network(*again.network(4), a);
  }
}

TEST(NetworkStore, AFirstSchemaStoreLoadsAndIsContinuedWithoutNetworks) {
  // Written by fnet-analyze store before the store kept networks (the 60-disk run of run-file-v1).
  testing::TempDir dir;
  const fs::path path = dir.path() / "legacy-v1.h5";
  fs::copy_file(kStoreV1, path);
  const StoredRun old = read_store(path);
  EXPECT_EQ(old.schema, kStoreSchemaV1);
  ASSERT_EQ(old.frames.size(), 3u);
  EXPECT_EQ(old.has_network, (std::vector<bool>(3, false)));
  EXPECT_FALSE(read_network(path, 1).has_value());
  {
    StoreWriter w(path, "legacy-v1");
    EXPECT_FALSE(w.network(2).has_value());
    w.append(with_network(3, testing::lammps_frame(0)));
    expect_same_network(*w.network(3), testing::lammps_frame(0));
  }
  const StoredRun now = read_store(path);
  EXPECT_EQ(now.schema, kStoreSchema);
  ASSERT_EQ(now.frames.size(), 4u);
  EXPECT_EQ(now.has_network, (std::vector<bool>{false, false, false, true}));
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(now.frames[k].header, old.frames[k].header);
    EXPECT_EQ(now.frames[k].diagrams.normal.pd0, old.frames[k].diagrams.normal.pd0);
    EXPECT_EQ(now.frames[k].distances.value, old.frames[k].distances.value);
  }
}

TEST(NetworkStore, ASecondSchemaStoreLoadsAsTwoDimensionalAndIsContinuedWithAThreeDimensionalFrame) {
  // Written by fnet-analyze store before frames carried a dimension (tests/data/run-file-v2).
  testing::TempDir dir;
  const fs::path path = dir.path() / "legacy-v2.h5";
  fs::copy_file(kStoreV2, path);
  const StoredRun old = read_store(path);
  EXPECT_EQ(old.schema, kStoreSchemaV2);
  ASSERT_EQ(old.frames.size(), 3u);
  EXPECT_EQ(old.has_network, (std::vector<bool>(3, true)));
  const auto before = read_network(path, 2);
  ASSERT_TRUE(before.has_value());
  EXPECT_EQ(before->dimension, 2);
  EXPECT_EQ(before->particles.size(), 60u);
  EXPECT_GT(before->contacts.size(), 0u);
  for (const Particle& p : before->particles) EXPECT_EQ(p.z, 0.0);
  EXPECT_EQ(analyze_frame(*before).normal.pd0, old.frames[2].diagrams.normal.pd0);
  const Frame c = lifted(testing::lammps_frame(5));
  {
    StoreWriter w(path, "legacy-v2");
    expect_same_network(*w.network(2), *before);
    w.append(with_network(3, c));
  }
  const StoredRun now = read_store(path);
  EXPECT_EQ(now.schema, kStoreSchema);
  ASSERT_EQ(now.frames.size(), 4u);
  expect_same_network(*read_network(path, 2), *before);
  expect_same_network(*read_network(path, 3), c);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(now.frames[k].header, old.frames[k].header);
    EXPECT_EQ(now.frames[k].distances.value, old.frames[k].distances.value);
  }
}

}  // namespace
}  // namespace fnet
