#include "tests/e2e/service_process.hpp"

#include <fstream>
#include <iterator>
#include <regex>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"

namespace fnet::e2e {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

namespace {
const fs::path kLammps = fs::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";
}

fs::path lammps_run(const fs::path& dir, const std::vector<int>& source,
                    const std::function<void(int, std::vector<std::string>&)>& edit) {
  fs::create_directories(dir);
  std::ifstream index_in(kLammps / "index.csv");
  std::vector<std::string> index_rows;
  std::string line;
  std::getline(index_in, line);
  while (std::getline(index_in, line)) index_rows.push_back(line);
  std::ofstream index(dir / "index.csv");
  index << "frame,step,rho,Z\n";
  for (std::size_t k = 0; k < source.size(); ++k) {
    char from[32], to[32];
    std::snprintf(from, sizeof from, "frame_%04d", source[k]);
    std::snprintf(to, sizeof to, "frame_%04zu", k);
    fs::copy_file(kLammps / (std::string(from) + "_particles.csv"), dir / (std::string(to) + "_particles.csv"));
    const fs::path contacts_from = kLammps / (std::string(from) + "_contacts.csv"),
                   contacts_to = dir / (std::string(to) + "_contacts.csv");
    if (edit) {
      std::ifstream contacts_in(contacts_from);
      std::vector<std::string> rows;
      while (std::getline(contacts_in, line)) rows.push_back(line);
      edit(static_cast<int>(k), rows);
      std::ofstream contacts(contacts_to);
      for (const std::string& r : rows) contacts << r << "\n";
    } else {
      fs::copy_file(contacts_from, contacts_to);
    }
    const std::string& row = index_rows.at(source[k]);
    index << k << row.substr(row.find(',')) << "\n";
  }
  return dir;
}

ServerProcess start_server(const fs::path& data_dir, int domain, const fs::path& log,
                           const std::vector<std::string>& flags, const std::string& program) {
  std::vector<std::string> args{"--data-dir", data_dir.string(), "--port", "0", "--domain", std::to_string(domain)};
  args.insert(args.end(), flags.begin(), flags.end());
  ServerProcess s;
  s.process = std::make_unique<Process>(program, args, log, dds_environment());
  const auto line = s.process->read_line(30s);
  if (!line) throw std::runtime_error("fnet-server did not start; see " + log.string());
  std::smatch m;
  if (!std::regex_search(*line, m, std::regex(":(\\d+) "))) throw std::runtime_error("no port in: " + *line);
  s.port = static_cast<unsigned short>(std::stoi(m[1]));
  return s;
}

std::optional<int> store_run(const fs::path& run_dir, const std::string& run_id, const fs::path& data_dir,
                             const fs::path& log, const std::string& ensemble) {
  std::vector<std::string> args{"store", "--csv-dir",  run_dir.string(), "--run-id",
                                run_id,  "--data-dir", data_dir.string()};
  if (!ensemble.empty()) args.insert(args.end(), {"--ensemble", ensemble});
  Process p(FNET_ANALYZE, args, log);
  return p.wait(300s);
}

std::optional<int> publish_run_file(const fs::path& file, int domain, const fs::path& log) {
  Process pub(FNET_ANALYZE,
              {"publish", "--run-file", file.string(), "--domain", std::to_string(domain), "--wait-for-reader", "30"},
              log, dds_environment());
  return pub.wait(std::chrono::seconds(120));
}

std::unique_ptr<Process> publish(const fs::path& run_dir, const std::string& run_id, int domain, const fs::path& log,
                                 double rate, double linger, double wait_for_reader, const std::string& ensemble) {
  std::vector<std::string> args{"publish",
                                "--csv-dir",
                                run_dir.string(),
                                "--run-id",
                                run_id,
                                "--domain",
                                std::to_string(domain),
                                "--rate",
                                std::to_string(rate),
                                "--linger",
                                std::to_string(linger),
                                "--wait-for-reader",
                                std::to_string(wait_for_reader)};
  if (!ensemble.empty()) args.insert(args.end(), {"--ensemble", ensemble});
  return std::make_unique<Process>(FNET_ANALYZE, args, log, dds_environment());
}

json wait_for_frames(unsigned short port, const std::string& run, std::size_t frames, std::chrono::seconds limit) {
  client::RpcClient rpc("127.0.0.1", port);
  const auto deadline = std::chrono::steady_clock::now() + limit;
  json last;
  while (std::chrono::steady_clock::now() < deadline) {
    const json listed = rpc.call("runs.list");  // iterating a temporary's member would dangle
    for (const json& r : listed["runs"])
      if (r["run"] == run) {
        last = r;
        if (r["frames"].get<std::size_t>() + r["rejected"].get<std::size_t>() >= frames && r["pending"] == 0) return r;
      }
    std::this_thread::sleep_for(100ms);
  }
  throw std::runtime_error("run " + run + " did not reach " + std::to_string(frames) + " frames: " + last.dump());
}

Outcome run_to_end(const std::string& program, const std::vector<std::string>& args, const fs::path& stderr_file,
                   const std::map<std::string, std::string>& env, std::chrono::seconds limit) {
  Process p(program, args, stderr_file, env);
  Outcome o;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!p.wait(0ms)) {
    if (const auto line = p.read_line(100ms))
      o.out += *line + "\n";
    else
      std::this_thread::sleep_for(10ms);
    if (std::chrono::steady_clock::now() > deadline) {
      p.stop();
      ADD_FAILURE() << program << " hung: " << ::testing::PrintToString(args);
    }
  }
  o.out += p.read_rest();
  o.code = p.wait(0ms).value_or(-1);
  o.err = read_file(stderr_file);
  return o;
}

Outcome run_fnetctl(unsigned short port, std::vector<std::string> args, const fs::path& stderr_file,
                    const std::map<std::string, std::string>& env) {
  args.insert(args.begin(), {"--port", std::to_string(port)});
  return run_to_end(FNETCTL, args, stderr_file, env);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace fnet::e2e
