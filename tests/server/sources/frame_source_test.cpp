// Every kind of input read through FrameSource: a run file and the CSV folder of the same
// fnet-simd run give the same frames, one by one in order; a frame's files give that frame; a file
// missing or cut short is named in the error.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/codec/frame_csv.hpp"
#include "common/store/run_file.hpp"
#include "server/sources/run_source.hpp"
#include "server/sources/source_kinds.hpp"
#include "tests/support/run_frame_compare.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::sources {
namespace {

namespace fs = std::filesystem;
namespace po = boost::program_options;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// A 60-disk run of 3 frames (seed 7) as fnet-simd wrote it: a run file and its CSV export.
const fs::path kRun = fs::path(FNET_TEST_DATA) / "run-file-v1";
const fs::path kRunFile = kRun / "legacy-v1.run.h5";
const fs::path kCsvDir = kRun / "csv";

// What store and publish open for these arguments.
std::unique_ptr<FrameSource> open_run(const std::vector<std::string>& args) {
  const std::vector<SourceKind> kinds = run_kinds();
  po::options_description options;
  add_run_options(kinds, options);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).run(), vm);
  po::notify(vm);
  return sources::open_run(kinds, vm);
}

std::vector<RunFrame> drain(FrameSource& source) {
  std::vector<RunFrame> frames;
  while (std::optional<RunFrame> f = source.next()) frames.push_back(std::move(*f));
  return frames;
}

// A copy of the CSV folder that a test may break.
fs::path copy_of_csv(const testing::TempDir& dir) {
  const fs::path copy = dir.path() / "csv";
  fs::copy(kCsvDir, copy);
  return copy;
}

TEST(FrameSource, RunFileAndCsvFolderOfOneRunYieldTheSameFrames) {
  const auto from_file = open_run({"--run-file", kRunFile.string()});
  const auto from_csv = open_run({"--csv-dir", kCsvDir.string(), "--run-id", "legacy-v1"});
  const RunInfo &file_info = from_file->announcement(), &csv_info = from_csv->announcement();
  EXPECT_EQ(file_info.run_id, "legacy-v1");
  EXPECT_EQ(csv_info.run_id, file_info.run_id);
  EXPECT_EQ(csv_info.particles, file_info.particles);
  EXPECT_EQ(csv_info.frames, file_info.frames);
  EXPECT_EQ(csv_info.config_json, "{}") << "a CSV folder records no parameters";
  std::vector<RunFrame> file_frames = drain(*from_file);
  const std::vector<RunFrame> csv_frames = drain(*from_csv);
  ASSERT_EQ(file_frames.size(), 3u);
  ASSERT_EQ(csv_frames.size(), file_frames.size());
  for (std::size_t k = 0; k < file_frames.size(); ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    EXPECT_EQ(file_frames[k].header.index, k);
    file_frames[k].wall_contacts.clear();  // the CSV folder's wall contacts are not read
    testing::expect_bit_exact(file_frames[k], csv_frames[k]);
  }
}

TEST(FrameSource, ARunFileOfTheCurrentSchemaYieldsTheFramesWrittenToIt) {
  const RunFileContents run = read_run_file(kRunFile);
  testing::TempDir dir;
  const fs::path path = dir.path() / "run.h5";
  {
    RunFileWriter writer(path, run.info);
    for (const RunFrame& f : run.frames) writer.append(f);
  }
  const auto source = open_run({"--run-file", path.string()});
  EXPECT_EQ(source->announcement(), run.info);
  const std::vector<RunFrame> frames = drain(*source);
  ASSERT_EQ(frames.size(), run.frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) testing::expect_bit_exact(run.frames[k], frames[k]);
}

TEST(FrameSource, FramesComeOneByOneThenTheInputEnds) {
  testing::TempDir dir;
  const fs::path csv = copy_of_csv(dir);
  const auto source = open_run({"--csv-dir", csv.string(), "--run-id", "r"});
  // A frame's files are read when it is asked for, not before.
  fs::remove(csv / "frame_0002_particles.csv");
  std::optional<RunFrame> f = source->next();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->header.index, 0u);
  f = source->next();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->header.index, 1u);
  EXPECT_THAT([&] { source->next(); },
              ThrowsMessage<std::exception>(
                  AllOf(HasSubstr((csv / "frame_0002_particles.csv").string()), HasSubstr("cannot open"))));

  const auto whole = open_run({"--csv-dir", kCsvDir.string(), "--run-id", "r"});
  EXPECT_EQ(drain(*whole).size(), 3u);
  EXPECT_FALSE(whole->next()) << "an input that has ended stays ended";
}

TEST(FrameSource, AFrameFileCutShortIsNamedWithItsLine) {
  testing::TempDir dir;
  const fs::path csv = copy_of_csv(dir);
  const fs::path contacts = csv / "frame_0001_contacts.csv";
  std::string text;
  {
    std::ifstream in(contacts, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Cut after the first field of line 4, as a writer stopped mid-row leaves it.
  std::size_t cut = 0;
  for (int line = 1; line < 4; ++line) cut = text.find('\n', cut) + 1;
  cut = text.find(',', cut) + 1;
  ASSERT_LT(cut, text.size());
  std::ofstream(contacts, std::ios::binary | std::ios::trunc) << text.substr(0, cut);
  const auto source = open_run({"--csv-dir", csv.string(), "--run-id", "r"});
  ASSERT_TRUE(source->next());
  EXPECT_THAT([&] { source->next(); },
              ThrowsMessage<std::exception>(AllOf(HasSubstr(contacts.string() + ":4:"), HasSubstr("fields"))));
}

TEST(FrameSource, AMissingIndexOrFrameOfACsvFolderIsNamed) {
  testing::TempDir dir;
  const fs::path csv = copy_of_csv(dir);
  fs::remove(csv / "frame_0000_contacts.csv");
  // The first frame is read when the folder is opened: its particles are announced.
  EXPECT_THAT(
      [&] {
        open_run({"--csv-dir", csv.string(), "--run-id", "r"});
      },
      ThrowsMessage<std::exception>(
          AllOf(HasSubstr((csv / "frame_0000_contacts.csv").string()), HasSubstr("cannot open"))));
  fs::remove(csv / "index.csv");
  EXPECT_THAT(
      [&] {
        open_run({"--csv-dir", csv.string(), "--run-id", "r"});
      },
      ThrowsMessage<std::exception>(HasSubstr((csv / "index.csv").string())));
}

TEST(FrameSource, ARunFileCutShortOrMissingIsNamed) {
  testing::TempDir dir;
  const fs::path cut = dir.path() / "cut.h5";
  fs::copy_file(kRunFile, cut);
  fs::resize_file(cut, fs::file_size(cut) / 2);
  EXPECT_THAT(
      [&] {
        drain(*open_run({"--run-file", cut.string()}));
      },
      ThrowsMessage<std::exception>(HasSubstr(cut.string())));
  const fs::path missing = dir.path() / "missing.h5";
  // A usage error, before any work.
  EXPECT_THAT(
      [&] {
        open_run({"--run-file", missing.string()});
      },
      ThrowsMessage<po::error>(AllOf(HasSubstr("--run-file"), HasSubstr(missing.string()), HasSubstr("no such file"))));
}

TEST(FrameSource, TheRunIdAndEnsembleGivenNameTheRunAndItsFrames) {
  const auto source = open_run({"--run-file", kRunFile.string(), "--run-id", "other", "--ensemble", "mu05"});
  EXPECT_EQ(source->announcement().run_id, "other");
  EXPECT_EQ(source->announcement().ensemble, "mu05");
  EXPECT_EQ(source->announcement().seed, 7u) << "the rest as the file records it";
  for (const RunFrame& f : drain(*source)) {
    EXPECT_EQ(f.header.run_id, "other");
    EXPECT_EQ(f.frame.label, frame_label("other", f.header.index));
  }
}

TEST(FrameSource, OneFramesFilesYieldThatFrameAlone) {
  const fs::path contacts = kCsvDir / "frame_0001_contacts.csv", particles = kCsvDir / "frame_0001_particles.csv";
  const Frame want = read_frame_csv(contacts, particles);
  for (const bool with_particles : {true, false}) {
    SCOPED_TRACE(with_particles ? "with particles" : "contacts alone");
    const auto source = open_frame_files(contacts, with_particles ? std::optional<fs::path>(particles) : std::nullopt);
    const RunFrame got = next_frame(*source);
    EXPECT_EQ(got.frame.label, contacts.string());
    EXPECT_EQ(got.frame.contacts.size(), want.contacts.size());
    EXPECT_EQ(got.frame.particles.size(), with_particles ? want.particles.size() : 0u);
    EXPECT_EQ(source->announcement().particles, got.frame.particle_count);
    EXPECT_FALSE(source->next());
  }
}

}  // namespace
}  // namespace fnet::sources
