// proto/store.md's h5py example, taken from the document at test time and run with python3 and
// h5py exactly as written, against real stores: one written by fnet-analyze store from the LAMMPS
// frames in tests/data, and the same store while a writer holds it open (a live store). What the
// example prints must be what the library reads back.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;
const fs::path kLammps = fs::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";

// The document's one ```python block.
std::string document_example() {
  std::ifstream in(fs::path(FNET_SOURCE_DIR) / "proto" / "store.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string open = "```python\n", close = "\n```";
  const std::size_t begin = doc.find(open);
  if (begin == std::string::npos) throw std::runtime_error("proto/store.md has no python example");
  if (doc.find(open, begin + 1) != std::string::npos) throw std::runtime_error("proto/store.md has two examples");
  const std::size_t end = doc.find(close, begin + open.size());
  return doc.substr(begin + open.size(), end - begin - open.size()) + "\n";
}

// A CSV run of the first `frames` LAMMPS frames.
fs::path lammps_run(const fs::path& dir, int frames) {
  fs::create_directories(dir);
  std::ifstream index_in(kLammps / "index.csv");
  std::ofstream index(dir / "index.csv");
  std::string line;
  for (int row = 0; row <= frames && std::getline(index_in, line); ++row) index << line << "\n";
  for (int k = 0; k < frames; ++k) {
    char name[32];
    for (const char* kind : {"particles", "contacts"}) {
      std::snprintf(name, sizeof name, "frame_%04d_%s.csv", k, kind);
      fs::copy_file(kLammps / name, dir / name);
    }
  }
  return dir;
}

// Runs the example in `dir`, where it finds data/demo.h5 as the document says.
std::string run_example(const fs::path& dir) {
  const fs::path script = dir / "store_example.py";
  std::ofstream(script) << document_example();
  const testing::ProcessResult r = testing::run_process(
      "/bin/sh", {"-c", "cd \"$1\" && exec \"$2\" \"$3\"", "sh", dir.string(), FNET_ORACLE_PYTHON, script.string()},
      dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

double number(const std::string& token) {
  std::size_t used = 0;
  const double v = std::stod(token, &used);
  if (used != token.size()) throw std::runtime_error("not a number: " + token);
  return v;
}

// The example's output against the store as the library reads it, value for value; networks[k]
// is the k-th frame's network as the library reads it back.
void expect_output_matches(const std::string& out, const StoredRun& store,
                           const std::vector<std::optional<Frame>>& networks) {
  ASSERT_EQ(networks.size(), store.frames.size());
  std::istringstream lines(out);
  std::string line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    rows.emplace_back(std::istream_iterator<std::string>(words), std::istream_iterator<std::string>());
  }
  ASSERT_EQ(rows.size(), store.frames.size() + 2) << out;
  EXPECT_EQ(rows.front(), (std::vector<std::string>{"run", store.info.run_id, "schema", kStoreSchema}));
  for (std::size_t k = 0; k < store.frames.size(); ++k) {
    SCOPED_TRACE("frame row " + std::to_string(k));
    const std::vector<std::string>& r = rows[k + 1];
    const AnalyzedFrame& f = store.frames[k];
    ASSERT_EQ(r.size(), networks[k] ? 19u : 15u) << out;
    EXPECT_EQ(r[0], "frame");
    EXPECT_EQ(number(r[1]), f.header.index);
    EXPECT_EQ(number(r[3]), f.header.rho);
    EXPECT_EQ(number(r[5]), f.previous ? static_cast<double>(*f.previous) : -1.0);
    EXPECT_EQ(number(r[7]), f.distances(Metric::wasserstein2, 1, ForceKind::normal));
    const Diagram& pd1 = f.diagrams.normal.pd1;
    EXPECT_EQ(number(r[9]), static_cast<double>(pd1.size()));
    if (pd1.empty()) {
      EXPECT_EQ(r[11], "-");
      EXPECT_EQ(r[12], "-");
    } else {
      EXPECT_EQ(number(r[11]), pd1.front().birth);
      EXPECT_EQ(number(r[12]), pd1.front().death);
    }
    if (!networks[k]) {
      EXPECT_EQ(r[13], "network");
      EXPECT_EQ(r[14], "-");
      continue;
    }
    const Frame& net = *networks[k];
    EXPECT_EQ(r[13], "grains");
    EXPECT_EQ(number(r[14]), static_cast<double>(net.particles.size()));
    EXPECT_EQ(number(r[16]), static_cast<double>(net.contacts.size()));
    ASSERT_FALSE(net.contacts.empty());
    double max_fn = net.contacts.front().fn;
    for (const Contact& c : net.contacts) max_fn = std::max(max_fn, c.fn);
    EXPECT_EQ(number(r[18]), max_fn);
  }
  EXPECT_FALSE(store.frames.back().diagrams.normal.pd1.empty());  // some point was compared
  const std::vector<std::string>& last = rows.back();
  ASSERT_EQ(last.size(), 4u) << out;
  EXPECT_EQ(number(last[1]), static_cast<double>(store.rejected.size()));
  ASSERT_FALSE(store.committed_at.empty());
  EXPECT_EQ(number(last[3]), *std::max_element(store.committed_at.begin(), store.committed_at.end()));
}

TEST(StoreDocument, ExampleReadsAStoreWrittenByFnetAnalyze) {
  testing::TempDir tmp;
  const fs::path run = lammps_run(tmp.path() / "csv", 3);
  const testing::ProcessResult analyzed = testing::run_process(
      FNET_ANALYZE,
      {"store", "--csv-dir", run.string(), "--run-id", "demo", "--data-dir", (tmp.path() / "data").string()},
      tmp.path());
  ASSERT_EQ(analyzed.exit_code, 0) << analyzed.err;
  const StoredRun store = read_store(store_path(tmp.path() / "data", "demo"));
  ASSERT_EQ(store.frames.size(), 3u);
  ASSERT_TRUE(store.frames[2].previous);
  EXPECT_GT(store.frames[2].distances(Metric::wasserstein2, 1, ForceKind::normal), 0);
  std::vector<std::optional<Frame>> networks;
  for (const AnalyzedFrame& f : store.frames)
    networks.push_back(read_network(store_path(tmp.path() / "data", "demo"), f.header.index));
  for (const auto& n : networks) ASSERT_TRUE(n.has_value());
  expect_output_matches(run_example(tmp.path()), store, networks);
}

TEST(StoreDocument, ExampleReadsALiveStoreAndItsNewFrames) {
  testing::TempDir tmp;
  const fs::path run = lammps_run(tmp.path() / "csv", 2);
  const testing::ProcessResult analyzed = testing::run_process(
      FNET_ANALYZE,
      {"store", "--csv-dir", run.string(), "--run-id", "demo", "--data-dir", (tmp.path() / "data").string()},
      tmp.path());
  ASSERT_EQ(analyzed.exit_code, 0) << analyzed.err;
  const fs::path path = store_path(tmp.path() / "data", "demo");
  const StoredRun before = read_store(path);
  ASSERT_EQ(before.frames.size(), 2u);
  // A writer continues the store and keeps it open, as a running server does.
  StoreWriter writer(path, "demo");
  std::vector<std::optional<Frame>> networks{writer.network(0), writer.network(1)};
  expect_output_matches(run_example(tmp.path()), read_store(path), networks);
  AnalyzedFrame next = before.frames[1];
  next.header.index = 2;
  next.previous = 1;
  next.distances.value[StepDistances::index(Metric::wasserstein2, 1, ForceKind::normal)] = 0.125;
  writer.append(next);
  const StoredRun after = read_store(path);
  ASSERT_EQ(after.frames.size(), 3u);
  networks.push_back(std::nullopt);  // appended without its network
  expect_output_matches(run_example(tmp.path()), after, networks);
}

}  // namespace
}  // namespace fnet
