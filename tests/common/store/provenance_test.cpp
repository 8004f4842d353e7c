// Every store and run file names the fnet that wrote it and when (root attributes fnet_version,
// fnet_commit, created; the store also its convention), read back by the library and by h5py;
// files written before these attributes existed read as "unknown".
#include <ctime>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "common/build_info/build_info.hpp"
#include "common/store/analysis_store.hpp"
#include "common/store/run_file.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

// Seconds between an ISO 8601 UTC stamp and now; fails the test for a malformed stamp.
double age_seconds(const std::string& stamp) {
  std::smatch m;
  const std::regex iso(R"((\d{4})-(\d{2})-(\d{2})T(\d{2}):(\d{2}):(\d{2})Z)");
  if (!std::regex_match(stamp, m, iso)) {
    ADD_FAILURE() << "not an ISO 8601 UTC time: '" << stamp << "'";
    return 1e9;
  }
  std::tm t{};
  t.tm_year = std::stoi(m[1]) - 1900;
  t.tm_mon = std::stoi(m[2]) - 1;
  t.tm_mday = std::stoi(m[3]);
  t.tm_hour = std::stoi(m[4]);
  t.tm_min = std::stoi(m[5]);
  t.tm_sec = std::stoi(m[6]);
  return std::difftime(std::time(nullptr), timegm(&t));
}

void expect_this_build(const FileProvenance& p) {
  EXPECT_EQ(p.fnet_version, build_info().version);
  EXPECT_EQ(p.fnet_commit, build_info().commit);
  EXPECT_TRUE(std::regex_match(p.fnet_commit, std::regex("[0-9a-f]{40}(-dirty)?|unknown"))) << p.fnet_commit;
  const double age = age_seconds(p.created);
  EXPECT_GE(age, -2);
  EXPECT_LE(age, 120);
}

TEST(Provenance, VersionIsCMakesProjectVersion) {
  EXPECT_EQ(build_info().version, FNET_PROJECT_VERSION);
  EXPECT_EQ(version_line("x"), "x " FNET_PROJECT_VERSION " (commit " + std::string(build_info().commit) + ")");
}

TEST(Provenance, StoreRecordsItsWriterAndConvention) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "p.h5";
  { StoreWriter w(path, "p"); }
  const StoredRun s = read_store(path);
  expect_this_build(s.provenance);
  const fs::path script = dir.path() / "check.py";
  std::ofstream(script) << "import h5py, sys\n"
                           "f = h5py.File(sys.argv[1], 'r', libver='latest', swmr=True)\n"
                           "print(f.attrs['convention'], f.attrs['fnet_version'], f.attrs['fnet_commit'])\n";
  const fs::path out = dir.path() / "out.txt";
  ASSERT_EQ(
      std::system((std::string(FNET_ORACLE_PYTHON) + " " + script.string() + " " + path.string() + " > " + out.string())
                      .c_str()),
      0);
  std::string convention, version, commit;
  std::ifstream(out) >> convention >> version >> commit;
  EXPECT_EQ(convention, "floor");
  EXPECT_EQ(version, build_info().version);
  EXPECT_EQ(commit, build_info().commit);
}

TEST(Provenance, RunFileRecordsItsWriter) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "r.run.h5";
  { RunFileWriter w(path, RunInfo{"r", 3, 0.4, 0.5, 4000, 0.5, 0.8, 1e-3, 7e-4, 0.9, 2, 1, "{}", ""}); }
  expect_this_build(read_run_file(path).provenance);
}

TEST(Provenance, OlderFilesReadAsUnknown) {
  const fs::path data = fs::path(FNET_SOURCE_DIR) / "tests" / "data";
  const StoredRun s = read_store(data / "store-v1" / "legacy-v1.h5");
  EXPECT_EQ(s.provenance.fnet_version, "unknown");
  EXPECT_EQ(s.provenance.created, "unknown");
  const RunFileContents r = read_run_file(data / "run-file-v1" / "legacy-v1.run.h5");
  EXPECT_EQ(r.provenance.fnet_commit, "unknown");
}

}  // namespace
}  // namespace fnet
