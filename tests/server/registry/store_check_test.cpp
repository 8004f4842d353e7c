// A store the server did not write is checked by a child process under a deadline before the
// server reads it: what a check's exit, output, crash or silence makes of its store, the checks
// run side by side within their bound, an unchanged store checked once; then fnet-server's own
// check on real stores, one of them a global heap that HDF5 reads forever.
#include "server/registry/store_check.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <vector>

#include <gtest/gtest.h>

#include "common/analysis/frame_analysis.hpp"
#include "common/store/analysis_store.hpp"
#include "tests/support/lammps_frames.hpp"
#include "tests/support/store_damage.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A checker that runs `script` under /bin/sh with the store's path as $1.
StoreChecker shell_checker(const std::string& script, double seconds = 20, unsigned parallel = 2) {
  return StoreChecker({{"/bin/sh", "-c", script, "sh"}, seconds, parallel});
}

std::size_t lines_in(const fs::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

class StoreCheck : public ::testing::Test {
 protected:
  fs::path file(const std::string& name) { return tmp_.write(name, "not really a store"); }
  testing::TempDir tmp_;
};

TEST_F(StoreCheck, AStoreItsCheckPassesIsNotRefused) {
  const std::vector<fs::path> files{file("a.h5"), file("b.h5")};
  EXPECT_EQ(shell_checker("for f; do echo ok; done").refusals(files), std::vector<std::string>(2));
}

TEST_F(StoreCheck, AFailedCheckRefusesItsStoreWithWhatItSaidNamingTheFile) {
  const fs::path named = file("named.h5"), unnamed = file("unnamed.h5"), silent = file("silent.h5");
  EXPECT_EQ(shell_checker("echo \"$1: offsets not ascending\"; exit 1").refusals({named}).front(),
            named.string() + ": offsets not ascending");
  EXPECT_EQ(shell_checker("echo 'no such dataset'; echo 'HDF5-DIAG: a trace' >&2; exit 1").refusals({unnamed}).front(),
            unnamed.string() + ": no such dataset");
  EXPECT_EQ(shell_checker("exit 5").refusals({silent}).front(), silent.string() + ": its check failed (exit code 5)");
}

TEST_F(StoreCheck, ACheckThatCrashesRefusesItsStore) {
  const fs::path f = file("crash.h5");
  const std::string refused = shell_checker("kill -SEGV $$").refusals({f}).front();
  EXPECT_EQ(refused.rfind(f.string() + ": its check ended by signal " + std::to_string(SIGSEGV), 0), 0u) << refused;
}

TEST_F(StoreCheck, ACheckPastItsDeadlineIsKilledAndItsStoreRefused) {
  const fs::path f = file("slow.h5");
  const auto begin = Clock::now();
  const std::string refused = shell_checker("echo $$ > \"$1.pid\"; exec sleep 600", 0.5).refusals({f}).front();
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(10));
  EXPECT_EQ(refused, f.string() +
                         ": its check did not finish within 0.5 s (--store-check-seconds): HDF5 may loop "
                         "forever on a damaged file");
  std::ifstream pid_file(f.string() + ".pid");
  pid_t pid = 0;
  ASSERT_TRUE(pid_file >> pid);
  EXPECT_EQ(kill(pid, 0), -1) << "the check still runs";
  EXPECT_EQ(errno, ESRCH) << "the check was not reaped";
}

TEST_F(StoreCheck, ChecksRunSideBySideWithinTheirBound) {
  std::vector<fs::path> files;
  for (const char* name : {"s0.h5", "s1.h5", "s2.h5", "s3.h5", "s4.h5", "s5.h5"}) files.push_back(file(name));
  const auto begin = Clock::now();
  EXPECT_EQ(shell_checker("for f; do sleep 1; echo ok; done", 20, 3).refusals(files), std::vector<std::string>(6));
  const auto took = Clock::now() - begin;
  EXPECT_GE(took, std::chrono::seconds(2)) << "more than 3 checks ran at once";
  EXPECT_LT(took, std::chrono::seconds(6)) << "the checks ran one at a time";
}

TEST_F(StoreCheck, AChildChecksSeveralStoresEachWithTheWholeDeadline) {
  const std::vector<fs::path> files{file("a.h5"), file("b.h5"), file("c.h5")};
  const auto begin = Clock::now();
  EXPECT_EQ(shell_checker("for f; do sleep 0.8; echo ok; done", 2, 1).refusals(files), std::vector<std::string>(3));
  EXPECT_GE(Clock::now() - begin, std::chrono::milliseconds(2400)) << "the stores were not checked in turn";
}

TEST_F(StoreCheck, AStoreThatCrashesOrStallsItsCheckIsRefusedAndTheStoresAfterItAreCheckedAgain) {
  const fs::path a = file("a.h5"), crash = file("crash.h5"), b = file("b.h5"), slow = file("slow.h5"), c = file("c.h5");
  const std::vector<std::string> refused =
      shell_checker("for f; do case $f in *crash*) kill -SEGV $$;; *slow*) exec sleep 600;; esac; echo ok; done", 2, 1)
          .refusals({a, crash, b, slow, c});
  ASSERT_EQ(refused.size(), 5u);
  EXPECT_EQ(refused[0], "");
  EXPECT_EQ(refused[1].rfind(crash.string() + ": its check ended by signal " + std::to_string(SIGSEGV), 0), 0u)
      << refused[1];
  EXPECT_EQ(refused[2], "");
  EXPECT_EQ(refused[3].rfind(slow.string() + ": its check did not finish within 2 s", 0), 0u) << refused[3];
  EXPECT_EQ(refused[4], "");
}

TEST_F(StoreCheck, AnUnchangedStoreIsCheckedOnceAndAChangedOneAgain) {
  const fs::path good = file("good.h5"), bad = file("bad.h5"), runs = tmp_.path() / "runs";
  StoreChecker checker = shell_checker("for f; do echo \"$f\" >> " + runs.string() +
                                       "; case $f in *bad*) echo bad;; *) echo ok;; esac; done");
  const std::vector<std::string> first = checker.refusals({good, bad});
  EXPECT_EQ(first, checker.refusals({good, bad}));
  EXPECT_EQ(lines_in(runs), 2u);
  EXPECT_TRUE(first[0].empty());
  EXPECT_EQ(first[1], bad.string() + ": bad");
  std::ofstream(bad, std::ios::app) << "more";
  checker.refusals({good, bad});
  EXPECT_EQ(lines_in(runs), 3u);
}

TEST_F(StoreCheck, OnlyRegularFilesAreChecked) {
  const fs::path fifo = tmp_.path() / "pipe.h5", missing = tmp_.path() / "missing.h5", runs = tmp_.path() / "runs";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(shell_checker("for f; do echo \"$f\" >> " + runs.string() + "; echo no; done").refusals({fifo, missing}),
            std::vector<std::string>(2));
  EXPECT_FALSE(fs::exists(runs));
}

TEST_F(StoreCheck, AStoreThatChangesWhileCheckedIsRefusedUntilCheckedUnchanged) {
  const fs::path f = file("growing.h5"), grown = tmp_.path() / "grown";
  StoreChecker checker = shell_checker("if [ ! -e " + grown.string() + " ]; then echo x >> \"$1\"; touch " +
                                       grown.string() + "; fi; echo ok");
  EXPECT_EQ(checker.refusals({f}).front(),
            f.string() + ": it changed while it was checked (a store is read once its writer has finished)");
  EXPECT_EQ(checker.refusals({f}).front(), "");
}

// fnet-server's own check of real stores: two frames with their networks.
class ServerStoreCheck : public ::testing::Test {
 protected:
  fs::path store(const std::string& run) {
    const fs::path path = tmp_.path() / (run + ".h5");
    StoreWriter w(path, run);
    for (const std::uint32_t index : {0u, 1u}) {
      const Frame network = testing::lammps_frame(index);
      AnalyzedFrame f;
      f.header = {run, index, 100ull * index, 0.5, 0.8, 3.5};
      f.dimension = network.dimension;
      f.diagrams = analyze_frame(network);
      if (index > 0) f.previous = index - 1;
      f.network = std::make_shared<const Frame>(network);
      w.append(f);
    }
    return path;
  }
  StoreChecker checker(double seconds) {
    return StoreChecker({{FNET_SERVER, "--check-store-for", std::to_string(getpid())}, seconds, 2});
  }
  testing::TempDir tmp_;
};

TEST_F(ServerStoreCheck, AHealthyStorePassesAndEachDamageIsRefusedWithItsReason) {
  const fs::path good = store("good"), heap = store("heap"), contact = store("contact");
  testing::loop_global_heap(heap);
  // A contact of frame 0 names a grain the frame does not have: only its network's read finds it.
  testing::set_entry(contact, "contact_pairs", 5, 0, 2, 1'000'000);
  const auto begin = Clock::now();
  // 8 s: far longer than a healthy store's check takes, even under the sanitizers on a loaded machine.
  const std::vector<std::string> refused = checker(8).refusals({good, heap, contact});
  EXPECT_LT(Clock::now() - begin, std::chrono::seconds(30));
  EXPECT_EQ(refused[0], "");
  EXPECT_EQ(refused[1], heap.string() +
                            ": its check did not finish within 8 s (--store-check-seconds): HDF5 may "
                            "loop forever on a damaged file");
  EXPECT_NE(refused[2].find(contact.string() + ": frame "), std::string::npos) << refused[2];
  EXPECT_NE(refused[2].find("joins grains"), std::string::npos) << refused[2];
}

}  // namespace
}  // namespace fnet::server
