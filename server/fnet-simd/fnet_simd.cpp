// fnet-simd: the simulation daemon. Runs the paper's compression protocol and hands every frame
// to the sinks selected on the command line.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "common/build_info/build_info.hpp"
#include "common/run/run_names.hpp"
#include "server/dem/checkpoint.hpp"
#include "server/dem/csv_export.hpp"
#include "server/dem/diagnostics.hpp"
#include "server/dem/ensemble_plan.hpp"
#include "server/dem/initial_packing.hpp"
#include "server/dem/lammps_data.hpp"
#include "server/dem/protocol.hpp"
#include "server/dem/walls.hpp"
#include "server/dem/workers.hpp"
#include "server/fnet-simd/ensemble_runner.hpp"
#include "server/fnet-simd/output_sinks.hpp"

namespace po = boost::program_options;
namespace fs = std::filesystem;
using namespace fnet::sim;

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

std::string duration(double seconds) {
  if (seconds < 0 || !std::isfinite(seconds)) return "?";
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lldh%02lldm", s / 3600, s / 60 % 60);
  else
    std::snprintf(buf, sizeof buf, "%lldm%02llds", s / 60, s % 60);
  return buf;
}

void print_progress(const Progress& p) {
  if (p.phase == Phase::relax) {
    std::fprintf(stderr,
                 "fnet-simd: relaxing  step %lld  translational KE/grain %.3g (target %.3g)  rho %.4f  Z %.3f  %.0f "
                 "steps/s\n",
                 static_cast<long long>(p.step), p.kinetic_energy, p.relax_target, p.rho, p.z, p.steps_per_second);
  } else {
    std::fprintf(stderr, "fnet-simd: %s  rho %.4f  Z %.3f  frames %zu/%zu  step %lld/%lld  %.0f steps/s  ETA %s\n",
                 p.phase == Phase::done ? "done" : "compressing", p.rho, p.z, p.frames_done, p.frames,
                 static_cast<long long>(p.compress_step), static_cast<long long>(p.compress_steps), p.steps_per_second,
                 duration(p.eta_seconds).c_str());
  }
}

constexpr const char* kUsage =
    "usage: fnet-simd [options]\n"
    "\n"
    "Runs the compression of Kramár et al. (2014): 2D polydisperse frictional disks in a box of rough\n"
    "walls (sized so that the grains fill --rho-initial of it), relaxed from a square lattice with\n"
    "random velocities until the grains are at rest (velocities damped during the relaxation only),\n"
    "then compressed by walls moving inward at v_c until rho = rho_final, with frames at fixed time\n"
    "intervals over the compression.\n"
    "Units: lengths in d_ave, masses in the mean grain mass, speeds in d_ave/tau_c, times in tau_c\n"
    "(k_n in m g/d_ave as in the paper). Parameters: defaults, then --config, then flags.\n"
    "\n"
    "Output: --export-csv DIR writes DIR/index.csv (frame,step,time,rho,z) and per frame\n"
    "DIR/frame_NNNN_particles.csv (id,x,y,r), DIR/frame_NNNN_contacts.csv (i,j,fn,ft; the input of\n"
    "'fnet-analyze diagram') and DIR/frame_NNNN_wall_contacts.csv (grain,wall,side,fn,ft), and\n"
    "DIR/provenance.json (fnet's version and commit, the date, the run's parameters and seed).\n"
    "Frames are published on Cyclone DDS (topics fnet_RunInfo, fnet_ForceFrame; reliable, keep-all,\n"
    "transient-local) on --domain (default 0; fnet-server must use the same) unless --no-dds;\n"
    "--out FILE also writes them to an HDF5 run file. With DDS as the only output, a run whose frames\n"
    "no subscriber matched exits 3 (the frames are lost), naming the domain.\n"
    "\n"
    "Checkpoints: with --checkpoint FILE (default DIR/checkpoint.fnetsim with --export-csv) the state\n"
    "is saved after every frame, every --checkpoint-interval seconds and on SIGINT/SIGTERM;\n"
    "--resume continues from it and produces frames bitwise identical to an uninterrupted run.\n"
    "\n"
    "Ensembles: --ensemble NAME --seeds 1-20 --jobs 2 runs one realization per seed (run ids NAME-sSEED),\n"
    "at most --jobs at a time, each a child fnet-simd doing a single run as above with the other flags.\n"
    "Each realization needs files of its own: --out, --export-csv, --checkpoint and --write-lammps-data\n"
    "must hold {run} (the run id) or {seed}, e.g. --out runs/{run}.h5. Its checkpoint is the one named,\n"
    "else checkpoint.fnetsim in its CSV folder, else {run}.fnetsim; its stderr goes to the checkpoint's\n"
    "name with .log. Progress is one line per realization and change (started, frame K/N, finished,\n"
    "stopped, failed with its exit code). SIGINT/SIGTERM stops every running realization at its\n"
    "checkpoint (exit 130); the same command again resumes those and skips the ones whose checkpoint\n"
    "holds the last frame. Exit 1 when any realization failed (named), 2 for a bad command line.\n"
    "Threads: each realization takes --threads (default 1), so --jobs x --threads in all.\n"
    "\n"
    "options";

// Exit code of a finished run whose frames reached no one: DDS was its only output and no
// subscriber ever matched.
constexpr int kFramesLost = 3;

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

// --seeds: plans every realization (all command-line problems, each seed's start and any checkpoint
// against this command's parameters are checked before the first child starts), then runs them.
int run_as_ensemble(const po::parsed_options& parsed, const po::variables_map& vm, const Params& p,
                    const std::string& ensemble, const std::vector<std::string>& physics_flags) {
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
    for (const po::option& o : parsed.options) {
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
  return run_ensemble(ensemble, runs, jobs, !vm.count("quiet"), g_stop);
}

}  // namespace

int main(int argc, char** argv) try {
  // Handlers first: an ensemble starts its realizations with these signals blocked, so that a stop
  // that comes while one is starting is kept until here and then ends it cleanly at a checkpoint.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  {
    sigset_t stops;
    sigemptyset(&stops);
    sigaddset(&stops, SIGINT);
    sigaddset(&stops, SIGTERM);
    sigprocmask(SIG_UNBLOCK, &stops, nullptr);
  }
  const Params defaults;
  po::options_description options(kUsage);
  std::string config, export_dir, checkpoint_path, run_id, ensemble, lammps_data, out_file;
  double checkpoint_interval = 60, linger = 0, ack_timeout = 60;
  int domain = 0;
  unsigned threads = 1;
  options.add_options()("help,h", "show this help")("version", "print the version and commit, then exit")(
      "config", po::value(&config), "JSON object of parameters (keys: the names in --show-params)");
  // The physics flags come from the parameter table; their values are parsed by it (a count
  // given as "-5" is an error there, not a wrapped-around integer).
  std::vector<std::string> flags;
  for (const ParamField& f : param_fields()) {
    flags.push_back(flag_name(f).substr(2));
    options.add_options()(flags.back().c_str(), po::value<std::string>(),
                          (std::string(f.help) + " (default " + format_value(defaults, f) + ")").c_str());
  }
  options.add_options()("threads", po::value(&threads)->default_value(1),
                        "threads for the time steps (forces and the Gear step); the results are the same bits for any "
                        "count")("run-id", po::value(&run_id),
                                 "run identifier carried by every frame, [A-Za-z0-9._-]{1,64} (default "
                                 "<ensemble>-s<S> with --ensemble, else fnet-simd-seed<S>)")(
      "ensemble", po::value(&ensemble),
      "the ensemble of realizations (one setting, several seeds) this run belongs to, announced with it; "
      "[A-Za-z0-9._-]{1,64}")("export-csv", po::value(&export_dir), "write frames as CSV files into this directory")(
      "out", po::value(&out_file),
      "write the run (parameters and every frame) to this HDF5 file, readable while it is written (proto/run_file.md)")(
      "no-dds", "do not publish frames over DDS")("domain", po::value(&domain)->default_value(0),
                                                  "DDS domain id (configure Cyclone DDS with CYCLONEDDS_URI)")(
      "ack-timeout", po::value(&ack_timeout)->default_value(60),
      "seconds to wait at the end until every subscriber acknowledged every frame")(
      "linger", po::value(&linger)->default_value(0),
      "seconds to keep serving late subscribers from the durability history after the last frame")(
      "checkpoint", po::value(&checkpoint_path), "checkpoint file")(
      "checkpoint-interval", po::value(&checkpoint_interval)->default_value(60), "seconds between checkpoints")(
      "resume", "continue the run saved in the checkpoint file (its parameters are used)")(
      "write-lammps-data", po::value(&lammps_data), "write the initial state as a LAMMPS data file, then run")(
      "show-params", "print the parameters and derived constants as JSON and exit")("quiet,q",
                                                                                    "no progress reports on stderr")(
      "seeds", po::value<std::string>(),
      "run an ensemble (needs --ensemble): one realization per seed, a list of seeds and ranges such as 1-20 or "
      "1,3,5-7")("jobs", po::value<unsigned>()->default_value(1), "with --seeds: realizations run at once");
  // Set by the ensemble that started this run: "frame K" is written there after each frame.
  int events_fd = -1;
  po::options_description hidden;
  hidden.add_options()("events-fd", po::value(&events_fd));
  po::options_description all;
  all.add(options).add(hidden);
  po::variables_map vm;
  const po::parsed_options parsed = po::parse_command_line(argc, argv, all);
  po::store(parsed, vm);
  if (vm.count("help")) {
    std::cout << options << "\n";
    return 0;
  }
  if (vm.count("version")) {
    std::cout << fnet::version_line("fnet-simd") << "\n";
    return 0;
  }
  po::notify(vm);

  Params p = defaults;
  if (!config.empty()) {
    std::ifstream in(config);
    if (!in) throw std::invalid_argument(config + ": cannot open config file");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(config + ": not JSON (" + e.what() + ")");
    }
    apply_json(p, j);
  }
  for (const ParamField& f : param_fields()) {
    const std::string flag = flag_name(f).substr(2);
    if (vm.count(flag)) set_from_text(p, f, vm[flag].as<std::string>());
  }
  validate(p);
  if (vm.count("run-id")) {
    if (const std::string problem = fnet::run_id_problem(run_id); !problem.empty())
      throw po::error("--run-id: " + problem);
  }
  if (vm.count("ensemble")) {
    if (const std::string problem = fnet::name_problem(ensemble, "ensemble name"); !problem.empty())
      throw po::error("--ensemble: " + problem);
  }
  if (threads < 1 || threads > 256) throw po::error("--threads must be between 1 and 256");
  if (vm.count("seeds")) return run_as_ensemble(parsed, vm, p, ensemble, flags);
  if (!vm["jobs"].defaulted()) throw po::error("--jobs needs --seeds (it runs the realizations of an ensemble)");
  const bool resume = vm.count("resume") > 0;
  // The start is built before anything is written: it checks what needs the grains (the box
  // against the lattice, rho_final against the start's packing fraction).
  Simulation sim;
  if (!resume) sim = make_lattice(p);

  if (vm.count("show-params")) {
    const Params& shown = resume ? p : sim.params;
    const Constants c = derive(shown);
    nlohmann::json j = {{"params", to_json(shown)},
                        {"derived",
                         {{"tau_c", c.tau_c},
                          {"gamma_n", c.gamma_n},
                          {"dt", c.dt},
                          {"kt", c.kt},
                          {"wall_speed_internal", c.wall_speed}}}};
    if (!resume) j["derived"]["rho_initial"] = packing_fraction(sim);  // of the start the box makes
    std::cout << j.dump(2) << "\n";
    return 0;
  }

  if (checkpoint_path.empty() && !export_dir.empty())
    checkpoint_path = (fs::path(export_dir) / "checkpoint.fnetsim").string();
  if (resume) {
    if (checkpoint_path.empty()) throw po::error("--resume needs --checkpoint FILE or --export-csv DIR");
    flags.push_back("config");
    for (const std::string& flag : flags)
      if (vm.count(flag))
        throw po::error("--" + flag + " cannot change a resumed run (its parameters come from the checkpoint)");
  }
  const bool publish = !vm.count("no-dds");
  if (!publish && export_dir.empty() && out_file.empty())
    std::fprintf(stderr,
                 "fnet-simd: note: --no-dds and no --export-csv or --out: frames are computed but written nowhere\n");

  if (resume) {
    Restored r = load_checkpoint(checkpoint_path);
    sim = std::move(r.simulation);
    if (run_id.empty()) run_id = r.run_id;
    if (!ensemble.empty() && !r.ensemble.empty() && ensemble != r.ensemble)
      throw po::error("--ensemble " + ensemble + " contradicts the checkpoint's ensemble " + r.ensemble);
    if (ensemble.empty()) ensemble = r.ensemble;
    std::fprintf(stderr, "fnet-simd: resumed %s at step %lld (%zu of %zu frames done)\n", run_id.c_str(),
                 static_cast<long long>(sim.step), sim.next_frame, sim.params.frames);
  }
  if (run_id.empty() && !ensemble.empty()) {
    run_id = ensemble + "-s" + std::to_string(sim.params.seed);
    if (const std::string problem = fnet::run_id_problem(run_id); !problem.empty())
      throw po::error("--ensemble: the run id it makes, " + problem);
  }
  if (run_id.empty()) run_id = "fnet-simd-seed" + std::to_string(sim.params.seed);
  if (!lammps_data.empty()) write_lammps_data(sim, lammps_data);

  Workers workers(threads);
  RunOptions o;
  o.run_id = run_id;
  o.workers = &workers;
  const std::size_t first_frame = resume && sim.phase != Phase::relax ? sim.next_frame : 0;
  const fnet::RunInfo info = run_info(sim.params, run_id, ensemble);
  if (!export_dir.empty()) {
    prepare_csv_dir(export_dir, first_frame);
    write_csv_provenance(export_dir, info);
  }
  std::optional<RunFileSink> run_file;
  if (!out_file.empty()) run_file.emplace(out_file, info, resume, first_frame);
  std::optional<DdsSink> dds;
  if (publish) dds.emplace(static_cast<dds_domainid_t>(domain), info);
  // Frames only DDS carries are lost unless a subscriber takes them before fnet-simd exits.
  const bool dds_only = dds && export_dir.empty() && !run_file;
  if (events_fd >= 0) std::signal(SIGPIPE, SIG_IGN);  // a parent gone is no reason to die mid-frame
  const auto report_frame = [events_fd](const FrameSnapshot& f) {
    if (events_fd < 0) return;
    const std::string line = "frame " + std::to_string(f.index + 1) + "\n";
    (void)!::write(events_fd, line.data(), line.size());
  };
  if (!export_dir.empty() || run_file || dds || events_fd >= 0)
    o.sink = [&, dir = fs::path(export_dir)](const FrameSnapshot& f) {
      if (!dir.empty()) write_frame_csv(dir, f);
      if (!run_file && !dds) return report_frame(f);
      const fnet::RunFrame frame = run_frame(f);  // once for both outputs
      if (run_file) (*run_file)(frame);
      if (dds) {
        (*dds)(frame);
        if (dds_only && f.index == first_frame && !dds->subscriber_now())
          std::fprintf(stderr,
                       "fnet-simd: warning: no DDS subscriber matched on domain %d and no --out or --export-csv: "
                       "frames are kept for late subscribers only until fnet-simd exits (--linger)\n",
                       domain);
      }
      report_frame(f);
    };
  o.relaxed = [](const Relaxation& r) {  // once per run, also with --quiet
    if (r.capped)
      std::fprintf(stderr,
                   "fnet-simd: warning: relaxation stopped by --relax-max-time after %lld steps, translational "
                   "kinetic energy per grain %.3g above the target %.3g: compressing a start that is not at rest\n",
                   static_cast<long long>(r.steps), r.energy, r.target);
    else
      std::fprintf(stderr, "fnet-simd: relaxed in %lld steps: translational kinetic energy per grain %.3g < %.3g\n",
                   static_cast<long long>(r.steps), r.energy, r.target);
  };
  if (!checkpoint_path.empty()) {
    o.checkpoint = [&](const Simulation& s) { save_checkpoint(s, run_id, checkpoint_path, ensemble); };
    o.checkpoint_seconds = checkpoint_interval;
  }
  if (!vm.count("quiet")) o.progress = print_progress;
  o.should_stop = [] { return g_stop.load(); };

  const std::int64_t steps_before = sim.step;
  const auto started = std::chrono::steady_clock::now();
  const bool finished = run(sim, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const auto steps = static_cast<double>(sim.step - steps_before);
  if (!vm.count("quiet") || finished)
    std::fprintf(stderr,
                 "fnet-simd: %lld steps in %.2f s: %.0f steps/s, %.4g particle-steps/s (N = %zu, %u thread%s)\n",
                 static_cast<long long>(sim.step - steps_before), seconds, steps / seconds,
                 steps * static_cast<double>(sim.n) / seconds, sim.n, threads, threads == 1 ? "" : "s");
  run_file.reset();   // closed now: readers need not wait while late DDS subscribers are served
  bool lost = false;  // DDS was the only output and no subscriber ever took a frame
  if (dds) {
    if (!vm.count("quiet")) std::fprintf(stderr, "fnet-simd: waiting for subscribers to acknowledge every frame\n");
    dds->finish(ack_timeout, finished ? linger : 0, o.should_stop);
    lost = dds_only && !dds->reached_a_subscriber();
    if (lost)
      std::fprintf(stderr,
                   "fnet-simd: error: no DDS subscriber matched on domain %d during the run and there was no --out "
                   "or --export-csv: its frames were lost (is fnet-server running with --domain %d and the same "
                   "CYCLONEDDS_URI?)\n",
                   domain, domain);
  }
  if (!finished) {
    if (o.checkpoint) {
      o.checkpoint(sim);
      std::fprintf(stderr, "fnet-simd: stopped at step %lld; checkpoint %s (continue with --resume)\n",
                   static_cast<long long>(sim.step), checkpoint_path.c_str());
    } else {
      std::fprintf(stderr, "fnet-simd: stopped at step %lld (no checkpoint file)\n", static_cast<long long>(sim.step));
    }
    return 130;
  }
  return lost ? kFramesLost : 0;
} catch (const po::error& e) {
  std::cerr << "fnet-simd: " << e.what() << " (see --help)\n";
  return 2;
} catch (const std::invalid_argument& e) {  // a bad parameter value or config file
  std::cerr << "fnet-simd: " << e.what() << "\n";
  return 2;
} catch (const std::exception& e) {
  std::cerr << "fnet-simd: " << e.what() << "\n";
  return 1;
}
