#include "server/fnet-simd/single_run.hpp"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "common/run/run_names.hpp"
#include "server/dem/checkpoint.hpp"
#include "server/dem/csv_export.hpp"
#include "server/dem/diagnostics.hpp"
#include "server/dem/initial_packing.hpp"
#include "server/dem/lammps_data.hpp"
#include "server/dem/protocol.hpp"
#include "server/dem/walls.hpp"
#include "server/dem/workers.hpp"
#include "server/fnet-simd/output_sinks.hpp"
#include "server/fnet-simd/progress_report.hpp"

namespace fnet::sim {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

// Exit code of a finished run whose frames reached no one: DDS was its only output and no
// subscriber ever matched.
constexpr int kFramesLost = 3;
// Exit code of a finished run that a fnet-server reading it cannot store (its store fault).
constexpr int kStoreFault = 4;

}  // namespace

int run_single(SimdOptions options, const std::atomic<bool>& stop) {
  auto& [p, config, export_dir, checkpoint_path, run_id, ensemble, lammps_data, out_file, checkpoint_interval, linger,
         ack_timeout, domain, threads, events_fd, flags, given, vm] = options;
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
  o.relaxed = print_relaxation;  // once per run, also with --quiet
  if (!checkpoint_path.empty()) {
    o.checkpoint = [&](const Simulation& s) { save_checkpoint(s, run_id, checkpoint_path, ensemble); };
    o.checkpoint_seconds = checkpoint_interval;
  }
  if (!vm.count("quiet")) o.progress = print_progress;
  o.should_stop = [&stop] { return stop.load(); };

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
  bool lost = false;  // DDS was the only output and a subscriber lacks frames, or none ever matched
  bool store_fault = false;
  if (dds) {
    if (!vm.count("quiet")) std::fprintf(stderr, "fnet-simd: waiting for subscribers to acknowledge every frame\n");
    const Delivery delivery = dds->finish(ack_timeout, finished ? linger : 0, o.should_stop);
    const char* severity = dds_only ? "error" : "warning";
    const char* kept = dds_only ? "" : " (the run's --out or --export-csv has them)";
    if (delivery.lost_readers > 0)
      std::fprintf(stderr,
                   "fnet-simd: %s: %u DDS subscriber(s) went away during the run (stopped, or silent longer than "
                   "the DDS lease): they may lack frames%s\n",
                   severity, delivery.lost_readers, kept);
    if (!delivery.acknowledged)
      std::fprintf(stderr,
                   "fnet-simd: %s: a DDS subscriber had not acknowledged every frame after --ack-timeout %g s: the "
                   "frames it has not acknowledged may not have reached it%s\n",
                   severity, ack_timeout, kept);
    for (const std::string& fault : delivery.stores.faults)
      std::fprintf(stderr, "fnet-simd: error: run %s is not stored: %s\n", run_id.c_str(), fault.c_str());
    for (const std::string& late : delivery.stores.unconfirmed)
      std::fprintf(stderr, "fnet-simd: %s: run %s: %s after --ack-timeout %g s%s\n", severity, run_id.c_str(),
                   late.c_str(), ack_timeout, kept);
    store_fault = !delivery.stores.faults.empty();
    lost = dds_only && (delivery.lost_readers > 0 || !delivery.acknowledged || !delivery.stores.unconfirmed.empty());
    if (dds_only && !dds->reached_a_subscriber()) {
      lost = true;
      std::fprintf(stderr,
                   "fnet-simd: error: no DDS subscriber matched on domain %d during the run and there was no --out "
                   "or --export-csv: its frames were lost (is fnet-server running with --domain %d and the same "
                   "CYCLONEDDS_URI?)\n",
                   domain, domain);
    }
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
  return store_fault ? kStoreFault : lost ? kFramesLost : 0;
}

}  // namespace fnet::sim
