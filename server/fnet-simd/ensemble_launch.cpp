#include "server/fnet-simd/ensemble_launch.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/run/run_names.hpp"
#include "server/dem/checkpoint.hpp"
#include "server/dem/ensemble_plan.hpp"
#include "server/dem/initial_packing.hpp"
#include "server/fnet-simd/ensemble_runner.hpp"

namespace fnet::sim {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

// The flags that hold a path: in an ensemble each must name every realization's own file.
constexpr const char* kPathFlags[] = {"out", "export-csv", "checkpoint", "write-lammps-data"};

// The checkpoint a realization's parameters and its completion are read from.
std::string realization_checkpoint(const po::variables_map& vm, const std::string& run_id, std::uint64_t seed) {
  if (vm.count("checkpoint")) return expand_path_template(vm["checkpoint"].as<std::string>(), run_id, seed);
  if (vm.count("export-csv"))
    return (fs::path(expand_path_template(vm["export-csv"].as<std::string>(), run_id, seed)) / "checkpoint.fnetsim")
        .string();
  return run_id + ".fnetsim";
}

}  // namespace

int run_as_ensemble(const SimdOptions& options, std::atomic<bool>& stop) {
  const po::variables_map& vm = options.vm;
  const Params& p = options.params;
  const std::string& ensemble = options.ensemble;
  const std::vector<std::string>& physics_flags = options.physics_flags;
  if (ensemble.empty()) throw po::error("--seeds needs --ensemble NAME (the realizations are NAME-sSEED)");
  for (const auto& [flag, why] : {std::pair{"seed", "each realization takes its seed from --seeds"},
                                  std::pair{"run-id", "the realizations are NAME-sSEED"},
                                  std::pair{"resume", "the ensemble resumes its interrupted realizations by itself"},
                                  std::pair{"show-params", "it shows one run: give --seed instead"}})
    if (vm.count(flag)) throw po::error(std::string("--") + flag + " cannot be given with --seeds: " + why);
  const unsigned jobs = vm["jobs"].as<unsigned>();
  if (jobs < 1 || jobs > 256) throw po::error("--jobs must be between 1 and 256");
  std::vector<std::uint64_t> seeds;
  try {
    seeds = parse_seed_list(vm["seeds"].as<std::string>());
  } catch (const std::invalid_argument& e) {
    throw po::error(std::string("--seeds: ") + e.what());
  }
  for (const char* flag : kPathFlags)
    if (vm.count(flag) && !names_each_realization(vm[flag].as<std::string>()))
      throw po::error(std::string("--") + flag + " " + vm[flag].as<std::string>() +
                      ": in an ensemble every realization needs its own; put {run} or {seed} in it");

  std::vector<Realization> runs;
  for (const std::uint64_t seed : seeds) {
    Realization r;
    r.seed = seed;
    r.run_id = realization_run_id(ensemble, seed);
    if (const std::string problem = fnet::run_id_problem(r.run_id); !problem.empty())
      throw po::error("--ensemble: the run id it makes, " + problem);
    Params ps = p;
    ps.seed = seed;
    const Params planned = make_lattice(ps).params;  // checks the start each seed makes
    r.frames = planned.frames;
    r.checkpoint = realization_checkpoint(vm, r.run_id, seed);
    r.log = fs::path(r.checkpoint).replace_extension(".log");
    if (fs::exists(r.checkpoint)) {
      const Restored saved = load_checkpoint(r.checkpoint);
      const nlohmann::json had = to_json(saved.simulation.params), wants = to_json(planned);
      std::string differ;
      for (const auto& [key, value] : wants.items())
        if (!had.contains(key) || had[key] != value) differ += (differ.empty() ? "" : ", ") + key;
      if (!differ.empty() || saved.run_id != r.run_id || saved.ensemble != ensemble)
        throw po::error("--seeds: the checkpoint " + r.checkpoint.string() + " of " + r.run_id +
                        " holds another run (" + (differ.empty() ? "run id or ensemble" : differ) +
                        " differ): rerun the command that made it, or delete it to start that seed over");
      r.complete = saved.simulation.phase == Phase::done;
      r.resume = !r.complete;
      r.first_frame = saved.simulation.phase == Phase::relax ? 0 : saved.simulation.next_frame;
    }
    // What the child is given: the user's flags as typed, with its paths; a resumed one takes its
    // parameters from its checkpoint, as --resume demands, and its initial state was written when
    // it started (--write-lammps-data would now write the resumed state over it).
    for (const po::option& o : options.given) {
      const std::string& key = o.string_key;
      if (key == "seeds" || key == "jobs" || key == "checkpoint" || key == "events-fd") continue;
      if (r.resume && (key == "config" || key == "write-lammps-data" ||
                       std::find(physics_flags.begin(), physics_flags.end(), key) != physics_flags.end()))
        continue;
      r.args.push_back("--" + key);
      for (const std::string& v : o.value) r.args.push_back(expand_path_template(v, r.run_id, seed));
    }
    if (r.resume)
      r.args.push_back("--resume");
    else
      r.args.insert(r.args.end(), {"--seed", std::to_string(seed)});
    r.args.insert(r.args.end(), {"--checkpoint", r.checkpoint.string()});
    runs.push_back(std::move(r));
  }
  for (const Realization& r : runs)
    if (!r.log.parent_path().empty()) fs::create_directories(r.log.parent_path());
  const unsigned threads = vm["threads"].as<unsigned>();
  if (const unsigned cores = std::thread::hardware_concurrency(); cores > 0 && jobs * threads > cores)
    std::fprintf(stderr, "fnet-simd: note: --jobs %u x --threads %u = %u threads on %u cores\n", jobs, threads,
                 jobs * threads, cores);
  return run_ensemble(ensemble, runs, jobs, !vm.count("quiet"), stop);
}

}  // namespace fnet::sim
