// What the end-to-end tests do to the service, written once: LAMMPS reference frames as a CSV run
// folder, fnet-server started on a port it picks, runs stored or published by fnet-analyze,
// waiting for a run's frames, and fnetctl (or any program) run to its end. Every test passes its
// own DDS domain, so that the tests may run side by side.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/e2e/process.hpp"

namespace fnet::e2e {

// The LAMMPS frames `source` of tests/data as a CSV run folder `dir`, renumbered 0, 1, ...;
// `edit` may rewrite frame k's contact rows (to plant bad input).
std::filesystem::path lammps_run(const std::filesystem::path& dir, const std::vector<int>& source,
                                 const std::function<void(int, std::vector<std::string>&)>& edit = {});

struct ServerProcess {
  std::unique_ptr<Process> process;
  unsigned short port = 0;
};

// fnet-server on `data_dir` and DDS `domain`, listening on the port it picked (given port 0), read
// from its first line; `flags` follow; `program` is the build's fnet-server unless given. Throws,
// naming the log, when it does not start.
ServerProcess start_server(const std::filesystem::path& data_dir, int domain, const std::filesystem::path& log,
                           const std::vector<std::string>& flags = {"--threads", "2"},
                           const std::string& program = FNET_SERVER);

// fnet-analyze store of the run folder into `data_dir`: its exit code, nullopt if it did not end.
std::optional<int> store_run(const std::filesystem::path& run_dir, const std::string& run_id,
                             const std::filesystem::path& data_dir, const std::filesystem::path& log,
                             const std::string& ensemble = "");

// fnet-analyze publish of the run folder onto DDS `domain` (its --rate, --linger and
// --wait-for-reader), started.
std::unique_ptr<Process> publish(const std::filesystem::path& run_dir, const std::string& run_id, int domain,
                                 const std::filesystem::path& log, double rate = 0, double linger = 0,
                                 double wait_for_reader = 30, const std::string& ensemble = "");

// fnet-analyze publish --run-file `file` onto DDS `domain` (waiting up to 30 s for a reader), run
// to its end: its exit code, nullopt if it did not end within 120 s.
std::optional<int> publish_run_file(const std::filesystem::path& file, int domain, const std::filesystem::path& log);

// Polls runs.list until `run` has `frames` settled (committed or rejected) and none pending, and
// returns its summary; throws with the last summary seen after `limit`.
nlohmann::json wait_for_frames(unsigned short port, const std::string& run, std::size_t frames,
                               std::chrono::seconds limit = std::chrono::seconds(120));

struct Outcome {
  int code = -1;
  std::string out, err;
};

// Runs `program` to its end, its stdout read as it comes (a full pipe would stall it); its stderr
// goes to `stderr_file` (appended) and is returned whole. A program still running after `limit`
// is stopped and reported as a test failure.
Outcome run_to_end(const std::string& program, const std::vector<std::string>& args,
                   const std::filesystem::path& stderr_file, const std::map<std::string, std::string>& env = {},
                   std::chrono::seconds limit = std::chrono::seconds(120));

// fnetctl --port `port` `args`, run to its end.
Outcome run_fnetctl(unsigned short port, std::vector<std::string> args, const std::filesystem::path& stderr_file,
                    const std::map<std::string, std::string>& env = {});

std::string read_file(const std::filesystem::path& path);

}  // namespace fnet::e2e
