// Choosing a kind of input by the flags given: the usage errors come before anything is opened,
// and name the flags at fault. Two made-up kinds stand for those to come (a pattern pair, a
// switch that several kinds share).
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "server/sources/run_source.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {
namespace {

namespace po = boost::program_options;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

int opened = 0;

// An input of two frames that announces run "recorded".
class TwoFrames final : public FrameSource {
 public:
  TwoFrames() { info_.run_id = "recorded"; }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    if (next_ == 2) return std::nullopt;
    RunFrame f;
    f.header = {info_.run_id, next_, next_, 0, 0, 0};
    f.frame.label = frame_label(info_.run_id, next_++);
    return f;
  }

 private:
  RunInfo info_;
  std::uint32_t next_ = 0;
};

std::unique_ptr<FrameSource> open_two(const SourceArguments&) {
  ++opened;
  return std::make_unique<TwoFrames>();
}

const std::vector<SourceKind> kKinds = {
    {"recording",
     {{"recording", "F", "a recording"}, {"follow", "", "wait for frames still to come", {}, false}},
     true,
     open_two},
    {"dump",
     {{"atoms", "PATTERN", "atom files"}, {"pairs", "PATTERN", "pair files"}, {"follow", "", "", {}, false}},
     false,
     open_two},
};

po::variables_map parse(const std::vector<SourceKind>& kinds, const std::vector<std::string>& args, bool run) {
  po::options_description options;
  if (run)
    add_run_options(kinds, options);
  else
    add_source_options(kinds, options);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).run(), vm);
  po::notify(vm);
  return vm;
}

// The usage error of choosing among `kinds` with `args`; nothing may have been opened.
std::string usage_error(const std::vector<std::string>& args, bool run = false) {
  const int before = opened;
  try {
    const po::variables_map vm = parse(kKinds, args, run);
    if (run)
      open_run(kKinds, vm);
    else
      choose_source(kKinds, vm);
  } catch (const po::error& e) {
    EXPECT_EQ(opened, before) << "opened before the usage was checked";
    return e.what();
  }
  ADD_FAILURE() << "no usage error for " << ::testing::PrintToString(args);
  return "";
}

TEST(SourceKind, UsageLinesListEachKindsFlags) {
  EXPECT_EQ(run_usage(run_kinds()),
            "(--run-file F | --csv-dir DIR --run-id R | --lammps-atoms PATTERN --lammps-pairs PATTERN "
            "[--wall-types T,...] [--columns ROLE=NAME,...] [--check-balance TOL] [--rho log:LOG:COLUMN|column:NAME] "
            "[--dimension 2|3] [--lammps-log LOG] [--follow] [--idle-timeout SECONDS] --run-id R)");
  EXPECT_EQ(source_usage(frame_kinds()),
            "(--contacts C.csv [--particles P.csv] | --lammps-atoms FILE --lammps-pairs FILE [--wall-types T,...] "
            "[--columns ROLE=NAME,...] [--check-balance TOL] [--rho log:LOG:COLUMN|column:NAME] [--dimension 2|3] "
            "[--lammps-log LOG] [--timestep N])");
  EXPECT_EQ(run_usage(kKinds), "(--recording F [--follow] | --atoms PATTERN --pairs PATTERN [--follow] --run-id R)");
}

TEST(SourceKind, ExactlyOneKindIsChosenByItsFirstFlag) {
  EXPECT_THAT(usage_error({}), HasSubstr("give exactly one of --recording and --atoms"));
  EXPECT_THAT(usage_error({"--recording", "r", "--atoms", "a*", "--pairs", "p*"}), HasSubstr("exactly one"));
  const ChosenSource chosen =
      choose_source(kKinds, parse(kKinds, {"--atoms", "a*", "--pairs", "p*", "--follow"}, false));
  EXPECT_EQ(chosen.kind, &kKinds[1]);
  EXPECT_EQ(chosen.given, (SourceArguments{{"atoms", "a*"}, {"pairs", "p*"}, {"follow", ""}}));
}

TEST(SourceKind, AKindsFlagsAreCheckedBeforeItOpens) {
  EXPECT_THAT(usage_error({"--atoms", "a*"}), HasSubstr("--atoms needs --pairs"));
  EXPECT_THAT(usage_error({"--recording", "r", "--pairs", "p*"}), HasSubstr("--pairs does not go with --recording"));
  EXPECT_THAT(usage_error({"--atoms", "a*", "--pairs", "p*"}, true), HasSubstr("--atoms needs --run-id"));
  EXPECT_THAT(usage_error({"--recording", "r", "--run-id", "a b"}, true), HasSubstr("--run-id"));
  // A path that must be there is checked as the flag's.
  const std::vector<SourceKind> frames = frame_kinds();
  EXPECT_THAT(
      [&] {
        choose_source(frames, parse(frames, {"--contacts", "/nonexistent/c.csv"}, false));
      },
      ThrowsMessage<po::error>(AllOf(HasSubstr("--contacts /nonexistent/c.csv"), HasSubstr("no such file"))));
}

TEST(SourceKind, ASingleKindsFirstFlagIsRequired) {
  const std::vector<SourceKind> frames{frame_files_kind()};
  EXPECT_THROW(parse(frames, {"--particles", "p.csv"}, false), po::required_option);
  // Unless the kind marks it not required: a command with inputs of its own beside it.
  std::vector<SourceKind> beside{frame_files_kind()};
  beside.front().flags.front().required = false;
  EXPECT_NO_THROW(parse(beside, {"--particles", "p.csv"}, false));
}

TEST(SourceKind, TheRunIdGivenNamesAnInputThatAnnouncesNone) {
  const auto named = open_run(kKinds, parse(kKinds, {"--atoms", "a*", "--pairs", "p*", "--run-id", "dumped"}, true));
  EXPECT_EQ(named->announcement().run_id, "dumped");
  const auto own = open_run(kKinds, parse(kKinds, {"--recording", "r"}, true));
  EXPECT_EQ(own->announcement().run_id, "recorded");
  const RunFrame first = next_frame(*named);
  EXPECT_EQ(first.header.run_id, "dumped");
  EXPECT_EQ(first.frame.label, frame_label("dumped", 0));
  EXPECT_EQ(next_frame(*named).header.index, 1u);
  EXPECT_THROW(next_frame(*named), std::runtime_error) << "the input has ended";
}

TEST(SourceKind, RunIdAndEnsembleHelpNameTheKindsThatAnnounce) {
  po::options_description options;
  add_run_options(run_kinds(), options);
  EXPECT_EQ(options.find("run-id", false).description(),
            "run id (required with --csv-dir or --lammps-atoms; overrides the run file's)");
  EXPECT_EQ(options.find("ensemble", false).description(),
            "the ensemble of realizations the run belongs to (overrides the run file's; a CSV folder or a LAMMPS run "
            "has none)");
}

}  // namespace
}  // namespace fnet::sources
