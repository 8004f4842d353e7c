// The run announcement in the HDF5 files: the run file's root attributes and the analysis store's
// announcements carry every field, under the names proto/run_file.md lists.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "common/codec/run_info_json.hpp"
#include "common/store/analysis_store.hpp"
#include "common/store/run_file.hpp"
#include "tests/support/doc_names.hpp"
#include "tests/support/run_info_sample.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

std::set<std::string> root_attributes(const std::filesystem::path& path) {
  h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path.string());
  h5::Group root(H5Gopen2(file.get(), "/", H5P_DEFAULT), "open /");
  std::set<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::set<std::string>*>(out)->insert(name);
    return 0;
  };
  h5::check(H5Aiterate2(root.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "H5Aiterate2");
  return names;
}

TEST(RunInfoStore, RunFileRoundTripsEveryField) {
  testing::TempDir dir;
  const auto path = dir.path() / "run.h5";
  const RunInfo sample = testing::distinct_run_info();
  { RunFileWriter writer(path, sample); }
  testing::expect_same_fields(sample, read_run_file(path).info);
}

TEST(RunInfoStore, RunFileAttributesAreTheOnesItsDocumentLists) {
  testing::TempDir dir;
  const auto path = dir.path() / "run.h5";
  { RunFileWriter writer(path, testing::distinct_run_info()); }
  const std::string doc = testing::read_text(std::string(FNET_SOURCE_DIR) + "/proto/run_file.md");
  EXPECT_EQ(root_attributes(path), testing::first_column_names(doc, "## Root attributes"));
}

TEST(RunInfoStore, AnalysisStoreRoundTripsEveryField) {
  testing::TempDir dir;
  RunInfo sample = testing::distinct_run_info();
  sample.config_json = "{ \"mu\" : 0.5 }";  // kept as written, spaces included
  const auto path = store_path(dir.path(), sample.run_id);
  {
    StoreWriter writer(path, sample.run_id);
    writer.write_info(sample);
  }
  const StoredRun stored = read_store(path);
  ASSERT_TRUE(stored.has_info);
  testing::expect_same_fields(sample, stored.info);
  // A writer that continues the store copies the announcement.
  { StoreWriter writer(path, sample.run_id); }
  testing::expect_same_fields(sample, read_store(path).info);
}

// The store records the JSON codec's verbatim form; its keys are the ones proto/store.md lists.
TEST(RunInfoStore, AnalysisStoreKeysAreTheOnesItsDocumentLists) {
  const std::string doc = testing::read_text(std::string(FNET_SOURCE_DIR) + "/proto/store.md");
  std::set<std::string> keys;
  const nlohmann::json json = to_json(testing::distinct_run_info(), JsonText::verbatim);
  for (const auto& [key, value] : json.items()) keys.insert(key);
  EXPECT_EQ(keys, testing::backticked_between(doc, "as JSON; the last row is the current one. Keys:", "|"));
}

}  // namespace
}  // namespace fnet
