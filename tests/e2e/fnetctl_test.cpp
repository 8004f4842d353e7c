// fnetctl as users run it, against a real fnet-server on loopback: its options and their errors,
// what its tables and CSV print, the diagram JSON it writes (read back by fnet-analyze distance),
// and `watch` waiting for a run, marking it complete and restoring the terminal.
#include <signal.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>
#include <sys/wait.h>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "tests/e2e/process.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::json;
using client::RpcClient;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using namespace std::chrono_literals;

// The first `frames` LAMMPS frames as a run folder.
fs::path first_frames(const fs::path& dir, int frames) {
  std::vector<int> source(static_cast<std::size_t>(frames));
  std::iota(source.begin(), source.end(), 0);
  return lammps_run(dir, source);
}

// One scratch directory, one DDS domain and (once started) one fnet-server per test.
class Fnetctl : public ::testing::Test {
 protected:
  ~Fnetctl() override {
    if (server_) server_->stop();
  }

  // Analyzes the first `frames` LAMMPS frames offline into the data directory as run `run`.
  void store_run(const std::string& run, int frames) {
    const fs::path csv = first_frames(tmp_.path() / ("csv-" + run), frames);
    ASSERT_EQ(e2e::store_run(csv, run, data_dir(), tmp_.path() / "store.log"), 0)
        << "fnet-analyze store failed; see " << tmp_.path() / "store.log";
  }

  // Starts fnet-server on an ephemeral port; it loads the stores already in the data directory.
  void start_server(int domain) {
    domain_ = domain;
    ServerProcess s = e2e::start_server(data_dir(), domain, tmp_.path() / "server.log", {});
    server_ = std::move(s.process);
    port_ = s.port;
  }

  // Streams the first `frames` LAMMPS frames as run `run` onto the server's DDS domain.
  std::unique_ptr<Process> publish(const std::string& run, int frames, double rate = 0) {
    const fs::path csv = first_frames(tmp_.path() / ("pub-" + run), frames);
    return e2e::publish(csv, run, domain_, tmp_.path() / ("publish-" + run + ".log"), rate);
  }

  // Runs fnetctl to its end with `args` after the server's --port.
  Outcome ctl(std::vector<std::string> args, const std::map<std::string, std::string>& env = {}) {
    return run_fnetctl(static_cast<unsigned short>(port_), std::move(args), next_stderr(), env);
  }

  Outcome run(const std::string& program, const std::vector<std::string>& args,
              const std::map<std::string, std::string>& env = {}) {
    return run_to_end(program, args, next_stderr(), env);
  }

  // Waits until the server has committed `frames` frames of `run`.
  void wait_for_frames(const std::string& run, std::size_t frames) {
    e2e::wait_for_frames(static_cast<unsigned short>(port_), run, frames, 300s);
  }

  json call(const std::string& method, const json& params = json::object()) {
    return RpcClient("127.0.0.1", static_cast<unsigned short>(port_)).call(method, params);
  }

  fs::path data_dir() const { return tmp_.path() / "data"; }
  const fs::path& scratch() const { return tmp_.path(); }
  int port() const { return port_; }

 private:
  fs::path next_stderr() { return tmp_.path() / ("stderr-" + std::to_string(++runs_)); }

  testing::TempDir tmp_;
  std::unique_ptr<Process> server_;
  int domain_ = 0, port_ = 0, runs_ = 0;
};

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string cell;
  for (std::stringstream s(text); std::getline(s, cell, sep);) out.push_back(cell);
  if (!text.empty() && text.back() == sep) out.emplace_back();
  return out;
}

// A CSV as rows of cells, the header first; the provenance comment that fnetctl writes first is
// checked (it names the server's build, fnetctl's and the time) and left out.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  const std::vector<std::string> lines = split(text, '\n');
  EXPECT_TRUE(
      !lines.empty() &&
      std::regex_search(lines[0], std::regex(R"(^# fnet-server \d+\.\d+\.\d+ \(commit [0-9a-f]{40}(-dirty)?\), )"
                                             R"(fnetctl \d+\.\d+\.\d+ \(commit .*\); .*; written \d{4}-)")))
      << "no provenance comment first: " << text.substr(0, 200);
  for (const std::string& line : lines)
    if (!line.empty() && line[0] != '#') rows.push_back(split(line, ','));
  return rows;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST_F(Fnetctl, QueryCsvRoundTripsTheServedDoublesBitForBit) {
  store_run("stored", 3);
  start_server(61);
  const Outcome o = ctl({"query", "--run", "stored", "--metric", "wasserstein2", "--dim", "1", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const json served = call("series.get", {{"run", "stored"}, {"metric", "wasserstein2"}, {"dim", 1}});
  const auto rows = parse_csv(o.out);
  ASSERT_EQ(rows.size(), 1 + served["frame"].size()) << o.out;
  const std::vector<std::string>& header = rows[0];
  for (const char* name : {"frame", "step", "time", "previous", "rho", "z", "value"})
    ASSERT_NE(std::find(header.begin(), header.end(), name), header.end()) << "no column " << name << ": " << o.out;
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t c_frame = column("frame"), c_step = column("step"), c_time = column("time"),
                    c_previous = column("previous"), c_rho = column("rho"), c_z = column("z"),
                    c_value = column("value");
  EXPECT_EQ(std::count(header.begin(), header.end(), "Z"), 0) << "one name for Z: z";
  for (std::size_t k = 0; k < served["frame"].size(); ++k) {
    const std::vector<std::string>& row = rows[k + 1];
    ASSERT_EQ(row.size(), header.size()) << o.out;
    EXPECT_EQ(row[c_frame], served["frame"][k].dump());
    EXPECT_EQ(row[c_step], served["step"][k].dump());
    EXPECT_TRUE(same_bits(std::stod(row[c_time]), served["time"][k].get<double>())) << row[c_time];
    EXPECT_TRUE(same_bits(std::stod(row[c_rho]), served["rho"][k].get<double>())) << row[c_rho];
    EXPECT_TRUE(same_bits(std::stod(row[c_z]), served["z"][k].get<double>())) << row[c_z];
    if (served["value"][k].is_null()) {
      EXPECT_EQ(row[c_value], "");  // no previous frame
      EXPECT_EQ(row[c_previous], "");
      continue;
    }
    EXPECT_EQ(row[c_previous], served["previous"][k].dump());
    EXPECT_TRUE(same_bits(std::stod(row[c_value]), served["value"][k].get<double>()))
        << row[c_value] << " vs " << served["value"][k].get<double>();
  }
}

// The rough edges a new user meets: a range past the last frame says where the frames are (exit
// 4), distance prints a table by default (JSON on request, the API's answer), and a watch for a
// run that never appears gives up after --wait naming the server's runs (exit 4). DDS domain 60.
TEST_F(Fnetctl, RangesPastTheEndDistanceTablesAndAWatchForAMissingRun) {
  store_run("stored", 3);
  start_server(60);
  const Outcome past = ctl({"query", "--run", "stored", "--metric", "bottleneck", "--from", "5"});
  EXPECT_EQ(past.code, 4) << past.out << past.err;
  EXPECT_THAT(past.err, AllOf(HasSubstr("no analyzed frame in the range asked (--from 5)"),
                              HasSubstr("from 0 to the last analyzed frame 2")));
  const Outcome inside = ctl({"query", "--run", "stored", "--metric", "bottleneck", "--from", "1", "--to", "9"});
  EXPECT_EQ(inside.code, 0) << inside.err;

  const json served =
      call("distance.get", {{"run", "stored"}, {"frame", 0}, {"other_frame", 2}, {"metric", "wasserstein2"}});
  const Outcome table =
      ctl({"distance", "--run", "stored", "--frame", "0", "--other-frame", "2", "--metric", "wasserstein2"});
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_THAT(table.out, AllOf(HasSubstr("run stored frame 0 -> stored frame 2: wasserstein2, PD1, normal"),
                               HasSubstr("exact   yes")));
  std::smatch value;
  ASSERT_TRUE(std::regex_search(table.out, value, std::regex(R"(value\s+(\S+))"))) << table.out;
  EXPECT_NEAR(std::stod(value[1]), served["value"].get<double>(), 1e-7 * served["value"].get<double>());
  const Outcome as_json = ctl({"distance", "--run", "stored", "--frame", "0", "--other-frame", "2", "--metric",
                               "wasserstein2", "--format", "json"});
  ASSERT_EQ(as_json.code, 0) << as_json.err;
  EXPECT_EQ(json::parse(as_json.out)["value"], served["value"]);

  const auto started = std::chrono::steady_clock::now();
  const Outcome missing = ctl({"watch", "--run", "stroed", "--wait", "2", "--plain"});
  EXPECT_EQ(missing.code, 4) << missing.out << missing.err;
  EXPECT_THAT(missing.err, AllOf(HasSubstr("run stroed has not appeared after 2 s"), HasSubstr("stored")));
  EXPECT_LT(std::chrono::steady_clock::now() - started, 30s);
  // An unknown run's error names the close ones.
  const Outcome unknown = ctl({"query", "--run", "stroed", "--metric", "bottleneck"});
  EXPECT_EQ(unknown.code, 4);
  EXPECT_THAT(unknown.err, HasSubstr("close: stored"));

  // A store written into the running server's data directory is served after fnetctl rescan; a
  // file that is not a store is named and left alone.
  store_run("later", 2);
  EXPECT_EQ(ctl({"query", "--run", "later", "--metric", "bottleneck"}).code, 4);
  std::ofstream(data_dir() / "broken.h5") << "not HDF5";
  const Outcome rescan = ctl({"rescan"});
  EXPECT_EQ(rescan.code, 5) << rescan.out << rescan.err;
  EXPECT_THAT(rescan.out, HasSubstr("adopted run later"));
  EXPECT_THAT(rescan.err, HasSubstr("broken.h5"));
  const json later = call("series.get", {{"run", "later"}, {"metric", "bottleneck"}});
  EXPECT_EQ(later["frame"].size(), 2u);
  EXPECT_EQ(ctl({"rescan"}).out.find("adopted"), std::string::npos) << "a known run is not adopted twice";
  std::ifstream broken(data_dir() / "broken.h5");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(broken), {}), "not HDF5");
}

TEST_F(Fnetctl, DiagramCsvRoundTripsTheServedPoints) {
  store_run("stored", 1);
  start_server(62);
  const Outcome o = ctl({"diagram", "--run", "stored", "--frame", "0", "--dim", "0", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const json served = call("diagram.get", {{"run", "stored"}, {"frame", 0}, {"dim", 0}});
  ASSERT_GT(served["points"].size(), 1u) << "a diagram with points";
  const auto rows = parse_csv(o.out);
  ASSERT_EQ(rows.size(), 1 + served["points"].size());
  EXPECT_EQ(rows[0], (std::vector<std::string>{"birth", "death"}));
  std::size_t differ = 0;
  std::string example;
  for (std::size_t k = 0; k < served["points"].size(); ++k)
    for (int c = 0; c < 2; ++c)
      if (!same_bits(std::stod(rows[k + 1][c]), served["points"][k][c].get<double>())) {
        if (!differ++) example = rows[k + 1][c] + " vs " + served["points"][k][c].dump();
      }
  EXPECT_EQ(differ, 0u) << "e.g. " << example;
}

TEST_F(Fnetctl, InfiniteDistancesPrintAsInfNotAsNoPreviousFrame) {
  store_run("stored", 4);
  start_server(63);
  const json served =
      call("series.get", {{"run", "stored"}, {"metric", "bottleneck"}, {"dim", 0}, {"essential", "separate"}});
  ASSERT_TRUE(served.contains("infinite")) << "the frames must change their number of never-dying classes";
  const std::vector<std::string> query{"query",       "--run",    "stored", "--metric", "bottleneck",
                                       "--essential", "separate", "--dim",  "0"};
  std::vector<std::string> csv_query = query;
  csv_query.insert(csv_query.end(), {"--format", "csv"});
  const auto rows = parse_csv(ctl(csv_query).out);
  const auto table = split(ctl(query).out, '\n');
  ASSERT_EQ(rows.size(), 1 + served["frame"].size());
  const std::size_t c_value = rows[0].size() - 1;
  ASSERT_EQ(rows[0][c_value], "value");
  std::size_t infinite = 0;
  for (std::size_t k = 0; k < served["frame"].size(); ++k) {
    const std::string row = *std::find_if(table.begin(), table.end(), [&](const std::string& line) {
      return std::regex_search(line, std::regex("^ *" + served["frame"][k].dump() + " "));
    });
    if (served["infinite"][k].get<bool>()) {
      ++infinite;
      EXPECT_EQ(rows[k + 1][c_value], "inf");
      EXPECT_THAT(row, HasSubstr(" inf"));
    } else if (served["value"][k].is_null()) {
      EXPECT_EQ(rows[k + 1][c_value], "");
      EXPECT_THAT(row, HasSubstr(" -"));
    } else {
      EXPECT_NE(rows[k + 1][c_value], "inf");
    }
  }
  EXPECT_GT(infinite, 0u);
  // JSON keeps what the API returns: null with infinite[k] = true.
  std::vector<std::string> json_query = query;
  json_query.insert(json_query.end(), {"--format", "json"});
  EXPECT_EQ(json::parse(ctl(json_query).out), served);
}

TEST_F(Fnetctl, DiagramJsonIsTheDocumentFnetAnalyzeDistanceReads) {
  store_run("stored", 2);
  start_server(64);
  for (const char* frame : {"0", "1"}) {
    const Outcome o =
        ctl({"diagram", "--run", "stored", "--frame", frame, "--force", "tangential", "--format", "json"});
    ASSERT_EQ(o.code, 0) << o.err;
    std::ofstream(scratch() / (std::string("frame") + frame + ".json")) << o.out;
  }
  for (int dim = 0; dim < 2; ++dim)
    for (const char* metric : {"bottleneck", "wasserstein2"}) {
      const Outcome d =
          run(FNET_ANALYZE, {"distance", (scratch() / "frame0.json").string(), (scratch() / "frame1.json").string(),
                             "--metric", metric, "--dim", std::to_string(dim)});
      ASSERT_EQ(d.code, 0) << d.err;
      const json served = call("distance.get", {{"run", "stored"},
                                                {"frame", 0},
                                                {"other_frame", 1},
                                                {"metric", metric},
                                                {"dim", dim},
                                                {"force", "tangential"}});
      EXPECT_TRUE(same_bits(json::parse(d.out)["value"].get<double>(), served["value"].get<double>()))
          << metric << " pd" << dim << ": " << d.out << " vs " << served.dump();
    }
}

TEST_F(Fnetctl, BadValuesAreUsageErrorsNamingTheFlag) {
  store_run("stored", 2);
  start_server(65);
  const auto usage_error = [&](std::vector<std::string> args, const std::string& flag) {
    const Outcome o = ctl(args);
    EXPECT_EQ(o.code, 2) << ::testing::PrintToString(args) << "\n" << o.out << o.err;
    EXPECT_THAT(o.err, HasSubstr(flag)) << ::testing::PrintToString(args);
    EXPECT_EQ(o.out, "") << ::testing::PrintToString(args);
  };
  usage_error({"query", "--metric", "bottleneck", "--q", "2"}, "--q");
  usage_error({"query", "--metric", "wasserstein"}, "--q");
  usage_error({"query", "--metric", "wasserstein1", "--from", "-3"}, "--from");
  usage_error({"query", "--metric", "wasserstein1", "--to", "-1"}, "--to");
  usage_error({"query", "--metric", "wasserstein1", "--from", "2", "--to", "1"}, "--from");
  usage_error({"query", "--metric", "geodesic"}, "--metric");
  usage_error({"query", "--metric", "bottleneck", "--dim", "2"}, "--dim");
  usage_error({"query", "--metric", "bottleneck", "--essential", "maybe"}, "--essential");
  usage_error({"distance", "--frame", "0", "--other-frame", "1", "--metric", "bottleneck", "--delta", "-0.1"},
              "--delta");
  usage_error({"distance", "--frame", "0", "--other-frame", "1", "--metric", "bottleneck", "--q", "3"}, "--q");
  usage_error({"diagram", "--frame", "-1"}, "--frame");
  usage_error({"diagram", "--frame", "0", "--force", "shear"}, "--force");
  for (const char* bad : {"2", "-1"}) usage_error({"watch", "--run", "stored", "--dim", bad}, "--dim");
  usage_error({"watch", "--run", "stored", "--force", "shear"}, "--force");
  usage_error({"watch", "--run", "stored", "--metric", "wasserstein"}, "--metric");
  usage_error({"query", "--metric", "bottleneck", "stray", "words"}, "unexpected argument 'stray' and 1 more");
}

TEST_F(Fnetctl, GlobalOptionsWorkAnywhereAndComeFromTheEnvironment) {
  store_run("stored", 1);
  start_server(66);
  const std::string port = std::to_string(this->port());
  // After the command.
  Outcome o = run(FNETCTL, {"runs", "--port", port});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_THAT(o.out, HasSubstr("stored"));
  o = run(FNETCTL, {"runs", "--host=127.0.0.1", "--port=" + port, "--format", "json"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(json::parse(o.out)["runs"][0]["run"], "stored");
  // From FNET_PORT / FNET_HOST, which the flags override.
  o = run(FNETCTL, {"runs"}, {{"FNET_PORT", port}, {"FNET_HOST", "127.0.0.1"}});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_THAT(o.out, HasSubstr("stored"));
  o = run(FNETCTL, {"--port", port, "runs"}, {{"FNET_PORT", "1"}});
  EXPECT_EQ(o.code, 0) << o.err;
  o = run(FNETCTL, {"runs"}, {{"FNET_PORT", port}, {"FNET_HOST", "no-such-host.invalid"}});
  EXPECT_EQ(o.code, 3);
  EXPECT_THAT(o.err, HasSubstr("no-such-host.invalid"));
  o = run(FNETCTL, {"runs"}, {{"FNET_PORT", "seventy"}});
  EXPECT_EQ(o.code, 2);
  EXPECT_THAT(o.err, AllOf(HasSubstr("FNET_PORT"), HasSubstr("seventy")));
  o = run(FNETCTL, {"runs", "--port"});
  EXPECT_EQ(o.code, 2);
  EXPECT_THAT(o.err, HasSubstr("--port"));
}

TEST_F(Fnetctl, RunsAreListedNewestActivityLast) {
  store_run("zz-stored", 1);  // loaded at start; sorts last by name, first by activity
  start_server(67);
  std::this_thread::sleep_for(2s);  // the stored run's last activity is its loading
  auto pub = publish("aa-live", 2);
  EXPECT_EQ(pub->wait(120s), 0);
  wait_for_frames("aa-live", 2);
  const Outcome o = ctl({"runs"});
  ASSERT_EQ(o.code, 0) << o.err;
  const auto first = o.out.find("zz-stored"), second = o.out.find("aa-live");
  ASSERT_NE(first, std::string::npos) << o.out;
  ASSERT_NE(second, std::string::npos) << o.out;
  EXPECT_LT(first, second) << o.out;
}

TEST_F(Fnetctl, StatusShowsTheIngestStateFirst) {
  start_server(70);
  const Outcome o = ctl({"status"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.out.rfind("ingest running\n", 0), 0u) << o.out;
}

TEST_F(Fnetctl, HelpListsEveryDistanceOptionAndEveryExitCode) {
  const Outcome o = run(FNETCTL, {"--help"});
  ASSERT_EQ(o.code, 0);
  const std::string distance =
      o.out.substr(o.out.find("  distance "), o.out.find("  status ") - o.out.find("  distance "));
  EXPECT_THAT(distance, AllOf(HasSubstr("--essential"), HasSubstr("--delta"), HasSubstr("--other-run"),
                              HasSubstr("--dim"), HasSubstr("--force"), HasSubstr("--q")));
  // deploy/README.md lists the same exit codes as --help, 1 included.
  std::ifstream readme(FNET_SOURCE_DIR "/deploy/README.md");
  const std::string text{std::istreambuf_iterator<char>(readme), {}};
  const auto at = text.find("**fnetctl** exit codes");
  ASSERT_NE(at, std::string::npos);
  // The item up to the next one, its line breaks and indentation read as spaces.
  const std::string listed = std::regex_replace(text.substr(at, text.find("\n- ", at) - at), std::regex("\\s+"), " ");
  for (const char* code : {"0 ok", "1 ", "2 bad usage", "3 server unreachable", "4 unknown run", "5 other server"})
    EXPECT_THAT(listed, HasSubstr(code)) << listed;
}

// Exit code 1: output fnetctl cannot write is a failure, not a silent success.
TEST_F(Fnetctl, OutputThatCannotBeWrittenExitsOne) {
  ASSERT_TRUE(fs::exists("/dev/full"));
  const std::string command = std::string(FNETCTL) + " --help > /dev/full 2> " + (scratch() / "full.err").string();
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream err(scratch() / "full.err");
  EXPECT_THAT(std::string(std::istreambuf_iterator<char>(err), {}), HasSubstr("cannot write"));
}

// The screen as the terminal shows it: what follows the last "enter the alternate screen".
bool restores_the_screen(const std::string& out) {
  const auto enter = out.rfind("\x1b[?1049h");
  return enter != std::string::npos && out.find("\x1b[?1049l", enter) != std::string::npos;
}

TEST_F(Fnetctl, WatchWaitsForTheRunMarksItCompleteAndRestoresTheScreen) {
  start_server(68);
  Process watch(FNETCTL, {"--port", std::to_string(port()), "watch", "--run", "late", "--until-complete"},
                scratch() / "watch.log");
  EXPECT_FALSE(watch.wait(3s)) << "watch gave up before the run existed";
  auto pub = publish("late", 3);
  ASSERT_EQ(watch.wait(300s), 0) << "see " << scratch() / "watch.log";
  EXPECT_EQ(pub->wait(60s), 0);
  const std::string out = watch.read_rest();
  EXPECT_THAT(out, AllOf(HasSubstr("waiting for run late"), HasSubstr("frames 3/3"), HasSubstr("complete"),
                         HasSubstr("min "), HasSubstr("max ")));
  EXPECT_THAT(out, Not(HasSubstr("\x1b[2J"))) << "clearing the screen floods the scrollback";
  ASSERT_TRUE(restores_the_screen(out));
  // What stays on the terminal once the alternate screen is gone: the last frame, as one line.
  EXPECT_THAT(out.substr(out.rfind("\x1b[?1049l")), AllOf(HasSubstr("frame 2 (frames 3/3)"), HasSubstr("complete")));
}

TEST_F(Fnetctl, WatchLeavesTheAlternateScreenOnCtrlC) {
  store_run("stored", 2);
  start_server(69);
  Process watch(FNETCTL, {"--port", std::to_string(port()), "watch", "--run", "stored"}, scratch() / "watch.log");
  // The stored run is drawn once both of its frames arrived.
  std::string seen;
  for (int k = 0; k < 100 && seen.find("frames 2/2") == std::string::npos; ++k)
    if (const auto line = watch.read_line(1s)) seen += *line + "\n";
  EXPECT_THAT(seen, AllOf(HasSubstr("frames 2/2"), HasSubstr("complete")));
  watch.signal(SIGINT);
  EXPECT_EQ(watch.wait(30s), 0);
  EXPECT_TRUE(restores_the_screen(seen + watch.read_rest()));
}

}  // namespace
}  // namespace fnet::e2e
