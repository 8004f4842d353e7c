// fnet-analyze's exit codes and messages as users meet them: usage errors (a bad flag, value or
// path) exit 2 naming what was wrong, before any work; input that cannot be analyzed exits 1.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/server/fnet-analyze/analyze_cli_fixture.hpp"

namespace fnet::testing {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

class AnalyzeCli : public AnalyzeCliTest {};

TEST_F(AnalyzeCli, StoreFromAMissingRunFileSaysNoSuchFile) {
  const std::string missing = (dir() / "nonexistent.h5").string();
  const std::string err = fails_with(2, {"store", "--run-file", missing, "--data-dir", (dir() / "d").string()});
  EXPECT_THAT(err,
              AllOf(HasSubstr("--run-file"), HasSubstr(missing), HasSubstr("no such file"), Not(HasSubstr("HDF5"))));
  EXPECT_FALSE(std::filesystem::exists(dir() / "d")) << "nothing is done before the input is checked";
  EXPECT_THAT(fails_with(2, {"store", "--csv-dir", (dir() / "nowhere").string(), "--run-id", "r", "--data-dir",
                             (dir() / "d").string()}),
              AllOf(HasSubstr("--csv-dir"), HasSubstr("no such directory")));
}

TEST_F(AnalyzeCli, AnEnsembleNameOutsideTheRunIdAlphabetIsAUsageError) {
  std::filesystem::create_directories(dir() / "csv");
  for (const char* command : {"store", "publish"}) {
    std::vector<std::string> args{command,      "--csv-dir", (dir() / "csv").string(), "--run-id", "r",
                                  "--ensemble", "mu 0.5"};
    if (std::string(command) == "store") args.insert(args.end(), {"--data-dir", (dir() / "d").string()});
    EXPECT_THAT(fails_with(2, args), AllOf(HasSubstr("--ensemble"), HasSubstr("mu 0.5"))) << command;
  }
  EXPECT_FALSE(std::filesystem::exists(dir() / "d")) << "nothing is done before the input is checked";
}

// An unquoted pattern (--lammps-atoms atoms.*.txt) reaches the command as one value and stray
// words: refused, naming the first, before any work.
TEST_F(AnalyzeCli, StrayArgumentsAreAUsageErrorNamingTheFirst) {
  std::filesystem::create_directories(dir() / "csv");
  const std::string csv = (dir() / "csv").string(), data = (dir() / "d").string();
  for (const char* command : {"store", "publish"}) {
    std::vector<std::string> args{command, "--csv-dir", csv, "atoms.1.txt", "atoms.2.txt", "--run-id", "r"};
    if (std::string(command) == "store") args.insert(args.end(), {"--data-dir", data});
    EXPECT_THAT(fails_with(2, args),
                AllOf(HasSubstr("unexpected argument 'atoms.1.txt' and 1 more"), HasSubstr("quote a file pattern")))
        << command;
  }
  EXPECT_THAT(fails_with(2, {"diagram", "--contacts", (dir() / "c.csv").string(), "stray"}),
              HasSubstr("unexpected argument 'stray'"));
  EXPECT_FALSE(std::filesystem::exists(dir() / "d")) << "nothing is done before the input is checked";
}

TEST_F(AnalyzeCli, StoreFromAFileThatIsNotHdf5FailsWithOne) {
  const auto text = write("notes.h5", "not HDF5\n");
  EXPECT_THAT(fails_with(1, {"store", "--run-file", text.string(), "--data-dir", (dir() / "d").string()}),
              HasSubstr(text.string()));
}

TEST_F(AnalyzeCli, StoreFromInputCutShortLeavesTheRunsStoreAsItWas) {
  namespace fs = std::filesystem;
  fs::copy(fs::path(FNET_TEST_DATA) / "run-file-v1" / "csv", dir() / "csv");
  const std::vector<std::string> args{"store", "--csv-dir",  (dir() / "csv").string(), "--run-id",
                                      "cut",   "--data-dir", (dir() / "d").string()};
  ASSERT_EQ(analyze(args).exit_code, 0);
  const fs::path store = dir() / "d" / "cut.h5";
  const auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string before = bytes(store);
  const fs::path last = dir() / "csv" / "frame_0002_contacts.csv";
  const std::string text = bytes(last);
  const std::size_t row = text.find('\n', text.size() / 2) + 1;  // a row cut after its first column
  std::ofstream(last, std::ios::trunc) << text.substr(0, text.find(',', row) + 1);
  EXPECT_THAT(fails_with(1, args), HasSubstr(last.string()));
  EXPECT_EQ(bytes(store), before) << "the store was touched before the input was read";
}

TEST_F(AnalyzeCli, DiagramWithAnUnknownForceIsAUsageError) {
  const auto contacts = write("c.csv", "i,j,fn,ft\n0,1,1,1\n");
  EXPECT_THAT(fails_with(2, {"diagram", "--contacts", contacts.string(), "--force", "shear"}),
              AllOf(HasSubstr("--force"), HasSubstr("shear")));
  EXPECT_THAT(fails_with(2, {"diagram", "--contacts", (dir() / "absent.csv").string()}),
              AllOf(HasSubstr("--contacts"), HasSubstr("no such file")));
}

TEST_F(AnalyzeCli, DistanceChecksItsOptionsWithTheSharedVocabulary) {
  const auto a = write("a.json", R"({"pd0":[],"pd1":[[1.0,0.8],[2.0,1.5]]})");
  const auto b = write("b.json", R"({"pd0":[],"pd1":[[1.0,0.9]]})");
  const auto usage = [&](std::vector<std::string> extra, const std::string& named) {
    std::vector<std::string> args{"distance", a.string(), b.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    EXPECT_THAT(fails_with(2, args), HasSubstr(named)) << ::testing::PrintToString(extra);
  };
  usage({"--metric", "bottleneck", "--q", "2"}, "--q");
  usage({"--metric", "wasserstein"}, "--q");
  usage({"--metric", "wasserstein", "--q", "0.5"}, "--q");
  usage({"--metric", "wasserstein1", "--q", "2"}, "--q");
  usage({"--metric", "earth-mover"}, "--metric");
  usage({"--metric", "bottleneck", "--dim", "2"}, "--dim");
  usage({"--metric", "bottleneck", "--essential", "maybe"}, "--essential");
  usage({"--metric", "bottleneck", "--delta", "-1"}, "--delta");
  EXPECT_THAT(fails_with(2, {"distance", a.string(), (dir() / "missing.json").string(), "--metric", "bottleneck"}),
              AllOf(HasSubstr("missing.json"), HasSubstr("no such file")));
  // A file that is there but holds no such diagram is bad input, not bad usage.
  const auto empty = write("empty.json", "{}");
  EXPECT_THAT(fails_with(1, {"distance", a.string(), empty.string(), "--metric", "bottleneck"}), HasSubstr("pd1"));

  const ProcessResult ok = analyze({"distance", a.string(), b.string(), "--metric", "wasserstein", "--q", "2"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const auto out = nlohmann::json::parse(ok.out);
  EXPECT_EQ(out["metric"], "wasserstein");
  EXPECT_EQ(out["q"], 2.0);
  EXPECT_EQ(out["dim"], 1);
}

// A document cut short or with a bad number is bad input: exit 1, the file and the place named.
TEST_F(AnalyzeCli, DistanceNamesTheFileAndPlaceOfABrokenDocument) {
  const auto a = write("a.json", R"({"pd0":[],"pd1":[[1.0,0.8],[2.0,1.5]]})");
  const auto cut = write("cut.json", R"({"pd0":[],"pd1":[[1.0,0.8],[2.0,1)");
  EXPECT_THAT(fails_with(1, {"distance", a.string(), cut.string(), "--metric", "bottleneck"}),
              AllOf(HasSubstr(cut.string()), HasSubstr("not JSON"), HasSubstr("column 34")));
  const auto bad = write("bad.json", "{\"pd0\":[],\n\"pd1\":[[1.0,0.8],[2.0,1.5.0]]}");
  EXPECT_THAT(fails_with(1, {"distance", bad.string(), a.string(), "--metric", "bottleneck"}),
              AllOf(HasSubstr(bad.string()), HasSubstr("line 2, column 26")));
  const auto reversed = write("rev.json", R"({"pd1":[[1.0,0.8],[1.5,2.0]]})");
  EXPECT_THAT(fails_with(1, {"distance", a.string(), reversed.string(), "--metric", "bottleneck"}),
              AllOf(HasSubstr(reversed.string()), HasSubstr("pd1: point 1"), HasSubstr("birth 1.5 < death 2.0")));
}

// Loading HDF5 and DDS (and what they pull in) took several times longer than a 2 000-grain
// diagram: fnet-analyze links neither, and runs fnet-analyze-io, from its own directory, for the
// commands that need them.
TEST_F(AnalyzeCli, DiagramAndDistanceLoadNoHdf5OrDdsLibrary) {
  if (!std::filesystem::exists("/usr/bin/readelf")) GTEST_SKIP() << "no readelf";
  const ProcessResult elf = run_process("/usr/bin/readelf", {"--dynamic", FNET_ANALYZE}, dir());
  ASSERT_EQ(elf.exit_code, 0) << elf.err;
  ASSERT_THAT(elf.out, HasSubstr("NEEDED"));
  EXPECT_THAT(elf.out, AllOf(Not(HasSubstr("hdf5")), Not(HasSubstr("ddsc"))));

  const ProcessResult store = analyze({"store", "--help"});
  EXPECT_EQ(store.exit_code, 0) << store.err;
  EXPECT_THAT(store.out, AllOf(HasSubstr("--run-file"), HasSubstr("--data-dir")));
  EXPECT_THAT(fails_with(2, {"publish", "--no-such-flag"}),
              AllOf(HasSubstr("fnet-analyze publish"), HasSubstr("no-such-flag")));

  // A copy without fnet-analyze-io beside it says what is missing.
  const auto alone = dir() / "fnet-analyze";
  std::filesystem::copy_file(FNET_ANALYZE, alone);
  const ProcessResult r = run_process(alone.string(), {"store", "--help"}, dir());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, AllOf(HasSubstr("cannot run"), HasSubstr((dir() / "fnet-analyze-io").string())));
  const ProcessResult diagram = run_process(alone.string(), {"diagram", "--help"}, dir());
  EXPECT_EQ(diagram.exit_code, 0) << "the other commands need nothing beside it";
}

TEST_F(AnalyzeCli, HelpNamesTheExitCodes) {
  const ProcessResult r = analyze({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, AllOf(HasSubstr("exit codes"), HasSubstr("0 ok"), HasSubstr("1 "), HasSubstr("2 ")));
}

}  // namespace
}  // namespace fnet::testing
