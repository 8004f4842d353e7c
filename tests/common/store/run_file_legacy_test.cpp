// Run files of the earlier schemas still load: fnet-run-1 (one group per frame) and fnet-run-2
// (before frames carried a dimension). The fixtures in tests/data/run-file-v1 and run-file-v2
// were written by fnet-simd before each change, together with the CSV export of the same frames:
// both must give the same frames, bit for bit.
#include <filesystem>

#include <gtest/gtest.h>

#include "common/codec/run_csv.hpp"
#include "common/store/hdf5_io.hpp"
#include "common/store/run_file.hpp"
#include "tests/support/run_frame_compare.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

const fs::path kFixture = fs::path(FNET_TEST_DATA) / "run-file-v1";
const fs::path kFixtureV2 = fs::path(FNET_TEST_DATA) / "run-file-v2";

void expect_same_frames(const std::vector<RunFrame>& want, const std::vector<RunFrame>& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t k = 0; k < want.size(); ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    EXPECT_EQ(want[k].header, got[k].header);
    ASSERT_EQ(want[k].frame.particles.size(), got[k].frame.particles.size());
    EXPECT_EQ(got[k].frame.dimension, 2);
    ASSERT_EQ(want[k].frame.contacts.size(), got[k].frame.contacts.size());
    for (std::size_t c = 0; c < want[k].frame.contacts.size(); ++c) {
      const Contact &a = want[k].frame.contacts[c], &b = got[k].frame.contacts[c];
      ASSERT_TRUE(a.i == b.i && a.j == b.j && testing::same_bits(a.fn, b.fn) && testing::same_bits(a.ft, b.ft))
          << "contact " << c;
    }
    for (std::size_t p = 0; p < want[k].frame.particles.size(); ++p) {
      const Particle &a = want[k].frame.particles[p], &b = got[k].frame.particles[p];
      ASSERT_TRUE(testing::same_bits(a.x, b.x) && testing::same_bits(a.y, b.y) && testing::same_bits(a.r, b.r) &&
                  a.z == 0.0 && b.z == 0.0)
          << "particle " << p;
    }
  }
}

TEST(RunFileV1, FramesEqualTheCsvExportOfTheSameRun) {
  const RunFileContents run = read_run_file(kFixture / "legacy-v1.run.h5");
  EXPECT_EQ(run.info.run_id, "legacy-v1");
  EXPECT_EQ(run.info.particles, 60u);
  EXPECT_EQ(run.info.frames, 3u);
  EXPECT_EQ(run.info.seed, 7u);
  EXPECT_EQ(run.info.ensemble, "");  // announced before version 2
  ASSERT_EQ(run.frames.size(), 3u);
  for (const RunFrame& f : run.frames) EXPECT_EQ(f.frame.particle_count, 60u);
  expect_same_frames(read_csv_run(kFixture / "csv", "legacy-v1"), run.frames);
}

TEST(RunFileV2, FramesAreTwoDimensionalAndEqualTheCsvExportOfTheSameRun) {
  const RunFileContents run = read_run_file(kFixtureV2 / "legacy-v2.run.h5");
  EXPECT_EQ(run.info.run_id, "legacy-v2");
  EXPECT_EQ(run.info.particles, 60u);
  ASSERT_EQ(run.frames.size(), 3u);
  EXPECT_GT(run.frames[2].frame.contacts.size(), 0u);
  expect_same_frames(read_csv_run(kFixtureV2 / "csv", "legacy-v2"), run.frames);
}

// Resuming a run from an older file keeps its frames before the resume point, in the current schema.
TEST(RunFileLegacy, ResumingConvertsItToTheCurrentSchemaKeepingTheEarlierFrames) {
  for (const fs::path& fixture : {kFixture / "legacy-v1.run.h5", kFixtureV2 / "legacy-v2.run.h5"}) {
    SCOPED_TRACE(fixture.string());
    testing::TempDir dir;
    const fs::path path = dir.path() / "run.h5";
    fs::copy_file(fixture, path);
    const RunFileContents before = read_run_file(path);
    { RunFileWriter writer = RunFileWriter::reopen(path, 2); }
    const RunFileContents after = read_run_file(path);
    EXPECT_EQ(before.info, after.info);
    expect_same_frames({before.frames[0], before.frames[1]}, after.frames);
    const h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path.string());
    const h5::Group root(H5Gopen2(file.get(), "/", H5P_DEFAULT), "open /");
    EXPECT_EQ(h5::read_string(root.get(), "schema", path.string()), kRunFileSchema);
  }
}

}  // namespace
}  // namespace fnet
