// The analysis store's record times: written with every record, kept when a writer continues the
// store, and unknown (not invented) for a store written before they existed; the chunk cache its
// files are opened with.
#include "common/store/analysis_store.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "common/store/hdf5_io.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

AnalyzedFrame analyzed(std::uint32_t index) {
  AnalyzedFrame f;
  f.header = {"times", index, 10ull * index, 0.1 * index, 0.7, 3.5};
  f.diagrams.normal.pd1 = {{2.0, 1.0 + 0.1 * index}};
  if (index > 0) f.previous = index - 1;
  return f;
}

RunInfo info() {
  RunInfo i;
  i.run_id = "times";
  i.particles = 10;
  i.config_json = "{}";
  return i;
}

void write_run(const fs::path& path) {
  StoreWriter w(path, "times");
  w.write_info(info(), 100.5);
  w.append(analyzed(0), 200.25);
  w.append(RejectedFrame{1, "run times frame 1: bad"}, 300.125);
  w.append(analyzed(2), 250.0);
}

TEST(AnalysisStore, EveryRecordKeepsItsTimeAcrossAContinuedStore) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "times.h5";
  write_run(path);
  for (int reopened = 0; reopened < 2; ++reopened) {
    SCOPED_TRACE(reopened);
    const StoredRun s = read_store(path);
    EXPECT_EQ(s.announced_at, 100.5);
    EXPECT_EQ(s.committed_at, (std::vector<StoreTime>{200.25, 250.0}));
    EXPECT_EQ(s.rejected_at, (std::vector<StoreTime>{300.125}));
    EXPECT_EQ(s.last_activity(), 300.125);
    StoreWriter continued(path, "times");  // copies the records into a fresh file
  }
}

TEST(AnalysisStore, AStoreWithoutTimesHasUnknownActivity) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "times.h5";
  write_run(path);
  {  // what a store written before the times were kept looks like
    h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open");
    for (const char* name : {"announced_at", "committed_at", "rejected_at"})
      ASSERT_GE(H5Ldelete(f.get(), name, H5P_DEFAULT), 0) << name;
  }
  for (int reopened = 0; reopened < 2; ++reopened) {
    SCOPED_TRACE(reopened);
    const StoredRun s = read_store(path);
    ASSERT_EQ(s.frames.size(), 2u);
    ASSERT_EQ(s.committed_at.size(), 2u);
    EXPECT_TRUE(std::isnan(s.committed_at[0]) && std::isnan(s.committed_at[1]));
    EXPECT_TRUE(std::isnan(s.announced_at));
    EXPECT_FALSE(s.last_activity());
    StoreWriter continued(path, "times");
  }
  StoreWriter w(path, "times");
  w.append(analyzed(3), 400.0);  // new records have times again
  EXPECT_EQ(read_store(path).last_activity(), 400.0);
}

// Every store and run file is opened with a chunk cache of two of its largest chunks per
// dataset, not HDF5's 1 MiB: a server writing ten stores held some 50 MB of full chunks.
TEST(AnalysisStore, FilesAreOpenedWithABoundedChunkCache) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "times.h5";
  write_run(path);
  const h5::File file = h5::open_for_reading(path.string());
  const h5::PropertyList fapl(H5Fget_access_plist(file.get()), "H5Fget_access_plist");
  int elements = 0;
  std::size_t slots = 0, bytes = 0;
  double w0 = 0;
  ASSERT_GE(H5Pget_cache(fapl.get(), &elements, &slots, &bytes, &w0), 0);
  EXPECT_EQ(bytes, h5::kChunkCacheBytes);
  EXPECT_GE(bytes, 2 * 8192 * 2 * sizeof(double));  // two chunks of the points' 8192 rows of 2 doubles
  EXPECT_EQ(w0, 1.0);
}

}  // namespace
}  // namespace fnet
