// The HDF5 run file: round trip, reading with h5py, resuming, and surviving a killed writer.
#include "common/store/run_file.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_frame_compare.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

RunInfo info(const std::string& run) {
  return {run, 300, 0.4, 0.5, 4000, 0.5, 0.8, 1e-3, 7.19377e-4, 0.9, 12, 7, R"({"particles": 300, "mu": 0.5})", ""};
}

RunFrame frame(const std::string& run, std::uint32_t index, std::size_t contacts) {
  std::mt19937_64 rng(index);
  std::uniform_real_distribution<double> u(-5, 5);
  RunFrame f;
  f.header = {run, index, 100ull * index, 0.25 * index, 0.63 + 0.01 * index, 0.1 * index};
  f.frame.label = frame_label(run, index);
  f.frame.particle_count = 300;
  for (int k = 0; k < 300; ++k) f.frame.particles.push_back({u(rng), u(rng), 0.4 + 0.01 * (k % 20)});
  for (std::size_t k = 0; k < contacts; ++k)
    f.frame.contacts.push_back(
        {static_cast<std::int64_t>(k % 300), static_cast<std::int64_t>((k * 7 + 1) % 300), u(rng), std::fabs(u(rng))});
  if (index % 2) f.wall_contacts.push_back({3, u(rng), 0.25});
  if (index % 3 == 1) {  // every third frame is 3D
    f.frame.dimension = 3;
    for (Particle& p : f.frame.particles) p.z = u(rng);
  }
  return f;
}

using testing::expect_bit_exact;

TEST(RunFile, RoundTripIncludingAnEmptyFrame) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "run.h5";
  {
    RunFileWriter w(file, info("r1"));
    for (std::uint32_t k = 0; k < 5; ++k) w.append(frame("r1", k, k == 2 ? 0 : 50 * k + 10));
  }
  const RunFileContents got = read_run_file(file);
  EXPECT_EQ(got.info, info("r1"));
  ASSERT_EQ(got.frames.size(), 5u);
  for (std::uint32_t k = 0; k < 5; ++k) expect_bit_exact(frame("r1", k, k == 2 ? 0 : 50 * k + 10), got.frames[k]);
}

// Checks a run file with h5py as proto/run_file.md says to open it (SWMR), expecting `frames`
// committed frames of frame("py", k, 40).
int check_with_h5py(const fs::path& dir, const fs::path& file, std::uint32_t frames) {
  const fs::path script = dir / "check.py";
  std::ofstream(script) << "import h5py, sys, json\n"
                           "f = h5py.File(sys.argv[1], 'r', libver='latest', swmr=True)\n"
                           "assert f.attrs['schema'] == 'fnet-run-3', f.attrs['schema']\n"
                           "assert f.attrs['run_id'] == 'py'\n"
                           "assert json.loads(f.attrs['config_json'])['mu'] == 0.5\n"
                           "n = int(sys.argv[2])\n"
                           "assert list(f['frame'][:]) == list(range(n)), f['frame'][:]\n"
                           "p0, p1, c0, c1, w0, w1 = f['offsets'][1]\n"
                           "assert f['particles'][p0:p1].shape == (300, 3)\n"
                           "assert f['contact_pairs'][c0:c1].shape == (40, 2) and c1 - c0 == 40\n"
                           "assert abs(f['rho'][1] - 0.64) < 1e-15 and f['step'][1] == 100\n"
                           "assert f['wall_contact_forces'][w0:w1].shape == (1, 2)\n"
                           "print('ok')\n";
  const std::string cmd =
      std::string(FNET_ORACLE_PYTHON) + " " + script.string() + " " + file.string() + " " + std::to_string(frames);
  return std::system(cmd.c_str());
}

TEST(RunFile, ReadableWithH5py) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "run.h5";
  {
    RunFileWriter w(file, info("py"));
    for (std::uint32_t k = 0; k < 3; ++k) w.append(frame("py", k, 40));
  }
  EXPECT_EQ(check_with_h5py(dir.path(), file, 3), 0);
}

// h5py opens the file while the writer still has it open, and sees every frame appended so far.
TEST(RunFile, ReadableWithH5pyWhileItIsWritten) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "run.h5";
  RunFileWriter w(file, info("py"));
  for (std::uint32_t k = 0; k < 3; ++k) w.append(frame("py", k, 40));
  EXPECT_EQ(check_with_h5py(dir.path(), file, 3), 0);
  for (std::uint32_t k = 3; k < 5; ++k) w.append(frame("py", k, 40));
  EXPECT_EQ(check_with_h5py(dir.path(), file, 5), 0);
  const RunFileContents live = read_run_file(file);  // the library's reader too
  ASSERT_EQ(live.frames.size(), 5u);
  for (std::uint32_t k = 0; k < 5; ++k) expect_bit_exact(frame("py", k, 40), live.frames[k]);
}

// The example of proto/run_file.md, run as written on a file still being written.
TEST(RunFile, DocumentedExampleRunsOnALiveFile) {
  std::ifstream doc(FNET_RUN_FILE_DOC);
  ASSERT_TRUE(doc) << FNET_RUN_FILE_DOC;
  const std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
  const std::size_t begin = text.find("```python\n");
  ASSERT_NE(begin, std::string::npos) << "no python example in " << FNET_RUN_FILE_DOC;
  const std::size_t end = text.find("```", begin + 10);
  testing::TempDir dir;
  const fs::path script = dir.path() / "example.py", out = dir.path() / "out.txt", file = dir.path() / "run.h5";
  std::ofstream(script) << text.substr(begin + 10, end - begin - 10);
  RunFileWriter w(file, info("doc"));
  for (std::uint32_t k = 0; k < 4; ++k) w.append(frame("doc", k, 30));
  const std::string cmd =
      std::string(FNET_ORACLE_PYTHON) + " " + script.string() + " " + file.string() + " > " + out.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream printed(out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(printed, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);  // the attributes, then one line per frame
  EXPECT_EQ(lines[0], "fnet-run-3 doc 300");
  EXPECT_EQ(lines[2].rfind("1 100 3 ", 0), 0u) << lines[2];  // frame 1 is 3D
  EXPECT_EQ(lines[3].rfind("2 200 2 ", 0), 0u) << lines[3];
  EXPECT_NE(lines[2].find("(300, 3) (300,) (30, 2) (30, 2) 1"), std::string::npos) << lines[2];
}

TEST(RunFile, ReopenDropsFramesFromTheResumePointOn) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "run.h5";
  {
    RunFileWriter w(file, info("r2"));
    for (std::uint32_t k = 0; k < 6; ++k) w.append(frame("r2", k, 20));
  }
  {
    RunFileWriter w = RunFileWriter::reopen(file, 4);
    EXPECT_EQ(w.frames(), 4u);
    w.append(frame("r2", 4, 33));  // rewritten after a resume
  }
  const RunFileContents got = read_run_file(file);
  ASSERT_EQ(got.frames.size(), 5u);
  expect_bit_exact(frame("r2", 4, 33), got.frames[4]);
}

TEST(RunFile, KilledWriterLeavesEveryFlushedFrameReadable) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "run.h5";
  int done[2];
  ASSERT_EQ(pipe(done), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    close(done[0]);
    RunFileWriter w(file, info("killed"));
    for (std::uint32_t k = 0;; ++k) {
      w.append(frame("killed", k, 2000));
      const std::uint32_t written = k + 1;
      if (write(done[1], &written, sizeof written) != sizeof written) _exit(1);
    }
  }
  close(done[1]);
  std::uint32_t reported = 0, n = 0;
  while (reported < 7 && read(done[0], &n, sizeof n) == sizeof n) reported = n;
  kill(pid, SIGKILL);  // most likely in the middle of writing the next frame
  waitpid(pid, nullptr, 0);
  while (read(done[0], &n, sizeof n) == sizeof n) reported = n;
  close(done[0]);
  ASSERT_GE(reported, 7u) << "the writer died before it wrote 7 frames";
  const RunFileContents got = read_run_file(file);
  ASSERT_GE(got.frames.size(), reported);
  for (std::uint32_t k = 0; k < reported; ++k) expect_bit_exact(frame("killed", k, 2000), got.frames[k]);
}

TEST(RunFile, ErrorsNameTheFile) {
  testing::TempDir dir;
  const fs::path bogus = dir.path() / "not-hdf5.h5";
  std::ofstream(bogus) << "hello";
  try {
    read_run_file(bogus);
    FAIL() << "no error";
  } catch (const h5::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not-hdf5.h5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_run_file(dir.path() / "missing.h5"), h5::Error);
}

}  // namespace
}  // namespace fnet
