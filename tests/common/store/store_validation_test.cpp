// read_store refuses a damaged or hostile store, naming the file and why, in a bounded time: every
// committed row's offsets and counts checked (not only the last), metadata whose checksums fail,
// anything but a regular file, a run id that is not a file name.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "common/analysis/frame_analysis.hpp"
#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_io.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/store_damage.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Three frames of run `run`, each with its network: the store every case damages.
fs::path healthy_store(const fs::path& dir, const std::string& run) {
  const fs::path path = dir / (run + ".h5");
  StoreWriter w(path, run);
  RunInfo info;
  info.run_id = run;
  w.write_info(info);
  for (std::uint32_t k = 0; k < 3; ++k) {
    AnalyzedFrame f;
    Frame net = testing::lammps_frame(static_cast<int>(5 * k));
    f.header = {run, 2 * k, 100ull * k, 0.5, 0.8, 3.5};
    f.diagrams = analyze_frame(net);
    if (k > 0) f.previous = 2 * (k - 1);
    f.network = std::make_shared<const Frame>(std::move(net));
    w.append(f);
  }
  return path;
}

// The message read_store's h5::Error carries; fails when it reads the store.
std::string refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const h5::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "the store was read";
  return "";
}

struct Damage {
  const char* name;
  std::function<void(const fs::path&)> apply;
  const char* reason;
};

TEST(StoreValidation, EveryCommittedRowIsCheckedNotOnlyTheLast) {
  testing::TempDir dir;
  const std::vector<Damage> cases{
      {"a diagram ending past every point",
       [](const fs::path& p) { testing::set_entry(p, "offsets", 0, 1, 5, 1u << 30); }, "offsets not ascending"},
      {"points inside the frame before's", [](const fs::path& p) { testing::set_entry(p, "offsets", 1, 0, 5, 0); },
       "inside the frame before's"},
      {"a network ending before it starts",
       [](const fs::path& p) { testing::set_entry(p, "network_offsets", 0, 0, 4, 1u << 20); },
       "network_offsets not ordered"},
      {"a network with other grains than its counts",
       [](const fs::path& p) { testing::set_entry(p, "counts", 1, 0, 6, 17); }, "grains, its counts 17"},
      {"frames not ascending", [](const fs::path& p) { testing::set_entry(p, "frame", 2, 0, 0, 2); },
       "frame indices not ascending"},
      {"a previous frame after the frame", [](const fs::path& p) { testing::set_entry(p, "previous", 1, 0, 0, 9); },
       "is not an earlier frame"},
      {"a dimension of 7", [](const fs::path& p) { testing::set_entry(p, "dimension", 0, 0, 0, 7); }, "dimension 7"},
      {"a run id that is a path", [](const fs::path& p) { testing::rename_run(p, "../../escape"); },
       "has a character outside"},
  };
  for (const Damage& d : cases) {
    SCOPED_TRACE(d.name);
    const fs::path path = healthy_store(dir.path(), "run");
    read_store(path);  // healthy before the damage
    d.apply(path);
    const std::string why = refusal([&] { read_store(path); });
    EXPECT_NE(why.find(path.string()), std::string::npos) << why;
    EXPECT_NE(why.find(d.reason), std::string::npos) << why;
    fs::remove(path);
  }
}

TEST(StoreValidation, AContactNamingAGrainTheFrameLacksIsRefusedWhenTheNetworkIsRead) {
  testing::TempDir dir;
  const fs::path path = healthy_store(dir.path(), "run");
  testing::set_entry(path, "contact_pairs", 0, 1, 2, 1u << 30);
  EXPECT_NE(refusal([&] { read_network(path, 0); }).find("joins grains"), std::string::npos);
  EXPECT_TRUE(read_network(path, 2).has_value());  // the other frames are served
}

TEST(StoreValidation, ADatasetLargerThanTheFileIsRefusedBeforeItIsRead) {
  testing::TempDir dir;
  const fs::path path = healthy_store(dir.path(), "run");
  {
    const h5::PropertyList fapl = h5::latest_format();
    const h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), "open");
    const h5::Dataset points(H5Dopen2(f.get(), "points", H5P_DEFAULT), "open points");
    const hsize_t huge[2] = {hsize_t{1} << 40, 2};
    h5::check(H5Dset_extent(points.get(), huge), "extent");
  }
  EXPECT_NE(refusal([&] { read_store(path); }).find("more than the file's"), std::string::npos);
}

TEST(StoreValidation, AChecksumFailureInTheHeaderFailsWithinABoundedTime) {
  testing::TempDir dir;
  const fs::path path = healthy_store(dir.path(), "run");
  testing::flip_bits(path, 100, 101, 1);  // the root group's object header
  const auto begin = Clock::now();
  EXPECT_NE(refusal([&] { read_store(path); }).find(path.string()), std::string::npos);
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(5));
}

TEST(StoreValidation, AFifoIsRefusedWithoutBeingOpened) {
  testing::TempDir dir;
  const fs::path fifo = dir.path() / "pipe.h5";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  auto read = std::async(std::launch::async, [&] { return refusal([&] { read_store(fifo); }); });
  if (read.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
    ADD_FAILURE() << "read_store blocked on a FIFO";
    const int writer = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // releases the blocked open
    if (writer >= 0) close(writer);
  }
  EXPECT_NE(read.get().find("not a regular file"), std::string::npos);
}

TEST(StoreValidation, AStoreInADataDirectoryIsNamedAfterItsRun) {
  testing::TempDir dir;
  const fs::path path = healthy_store(dir.path(), "run");
  EXPECT_EQ(read_store_in_data_dir(path).info.run_id, "run");
  const fs::path other = dir.path() / "other.h5";
  fs::rename(path, other);
  EXPECT_NE(refusal([&] { read_store_in_data_dir(other); }).find("not the run its file name says"), std::string::npos);
}

}  // namespace
}  // namespace fnet
