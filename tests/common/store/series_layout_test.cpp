// The store names the columns of `distances` in its `series` attribute, and readers follow it:
// a store whose columns come in another order reads back the same distances; a store written
// before the attribute has the order fnet has always written.
#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_handle.hpp"
#include "common/store/hdf5_io.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

// The order of proto/store.md's column table, which stores without the attribute have.
constexpr const char* kWrittenOrder =
    "bottleneck/pd0/normal,bottleneck/pd0/tangential,bottleneck/pd1/normal,bottleneck/pd1/tangential,"
    "wasserstein1/pd0/normal,wasserstein1/pd0/tangential,wasserstein1/pd1/normal,wasserstein1/pd1/tangential,"
    "wasserstein2/pd0/normal,wasserstein2/pd0/tangential,wasserstein2/pd1/normal,wasserstein2/pd1/tangential";

// Frame k's distance c is 100 k + c + 1: every column of every frame tells where it came from.
AnalyzedFrame frame(std::uint32_t k) {
  AnalyzedFrame f;
  f.header = {"layout", k, k, 0.1 * k, 0.7, 3.5};
  if (k > 0) f.previous = k - 1;
  for (std::size_t c = 0; c < f.distances.value.size(); ++c)
    f.distances.value[c] = 100.0 * k + static_cast<double>(c) + 1;
  return f;
}

fs::path write_store(const fs::path& dir) {
  const fs::path path = dir / "layout.h5";
  StoreWriter w(path, "layout");
  for (std::uint32_t k = 0; k < 3; ++k) w.append(frame(k));
  return path;
}

// Rewrites the store's columns in reverse order, with `layout` as its attribute (none: deleted).
void reverse_columns(const fs::path& path, const std::optional<std::string>& layout) {
  h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open");
  const std::size_t n = kStoredSeries.size();
  std::vector<double> d = h5::read_doubles(f.get(), "distances", n, "test");
  for (std::size_t row = 0; row < d.size() / n; ++row) std::reverse(d.begin() + row * n, d.begin() + (row + 1) * n);
  const h5::Dataset set(H5Dopen2(f.get(), "distances", H5P_DEFAULT), "open distances");
  ASSERT_GE(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.data()), 0);
  ASSERT_GE(H5Adelete(f.get(), "series"), 0);
  if (layout) h5::write_attribute(f.get(), "series", *layout);
}

std::string reversed(const std::string& layout) {
  std::vector<std::string> keys;
  for (std::size_t at = 0; at <= layout.size();) {
    const std::size_t end = std::min(layout.find(',', at), layout.size());
    keys.push_back(layout.substr(at, end - at));
    at = end + 1;
  }
  std::string out;
  for (auto it = keys.rbegin(); it != keys.rend(); ++it) out += (out.empty() ? "" : ",") + *it;
  return out;
}

void expect_frames_as_written(const StoredRun& run) {
  ASSERT_EQ(run.frames.size(), 3u);
  for (std::uint32_t k = 0; k < 3; ++k) EXPECT_EQ(run.frames[k].distances.value, frame(k).distances.value) << k;
}

TEST(SeriesLayout, TheStoreNamesItsColumnsInTheOrderItHasAlwaysWritten) {
  testing::TempDir dir;
  const fs::path path = write_store(dir.path());
  h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open");
  EXPECT_EQ(h5::read_string(f.get(), "series", "test"), kWrittenOrder);
  EXPECT_EQ(stored_series_layout(), kWrittenOrder);
  // StepDistances(metric, dim, force) is the column the attribute names.
  const AnalyzedFrame a = frame(1);
  EXPECT_EQ(a.distances(Metric::wasserstein2, 1, ForceKind::normal), 100.0 + 10 + 1);
  EXPECT_EQ(a.distances(Metric::bottleneck, 0, ForceKind::tangential), 100.0 + 1 + 1);
}

TEST(SeriesLayout, ColumnsInAnotherOrderReadBackAsWritten) {
  testing::TempDir dir;
  const fs::path path = write_store(dir.path());
  reverse_columns(path, reversed(kWrittenOrder));
  expect_frames_as_written(read_store(path));
}

TEST(SeriesLayout, AStoreWithoutTheAttributeHasTheWrittenOrder) {
  testing::TempDir dir;
  const fs::path path = write_store(dir.path());
  {
    h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open");
    ASSERT_GE(H5Adelete(f.get(), "series"), 0);
  }
  expect_frames_as_written(read_store(path));
}

TEST(SeriesLayout, AnAttributeThatIsNoPermutationIsAnErrorNamingIt) {
  for (const std::string& bad :
       {std::string("bottleneck/pd0/normal"), std::string(kWrittenOrder).replace(0, 10, "bottleneckX"),
        std::string(kWrittenOrder).replace(22, 25, "bottleneck/pd0/normal")}) {  // one key, unknown, twice
    SCOPED_TRACE(bad);
    testing::TempDir dir;
    const fs::path path = write_store(dir.path());
    reverse_columns(path, bad);
    try {
      read_store(path);
      FAIL() << "read a store whose series attribute is " << bad;
    } catch (const h5::Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": attribute 'series'"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fnet
