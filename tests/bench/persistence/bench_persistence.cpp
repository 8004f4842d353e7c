// fnet's PD0 + PD1 against GUDHI's on the same synthetic packings, side by side: time, peak
// memory (each side in its own forked child), and a check that both give the same diagrams.
#include <malloc.h>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"
#include "tests/bench/persistence/child_process.hpp"
#include "tests/bench/persistence/median_time.hpp"
#include "tests/support/diagram_match.hpp"
#include "tests/support/gudhi_persistence.hpp"
#include "tests/support/synthetic_frame.hpp"

namespace fnet::bench {
namespace {

struct Options {
  std::vector<std::size_t> sizes;
  std::size_t gudhi_max = 0;
  double budget_s = 1;
  std::uint64_t seed = 1;
  bool steady_malloc = true;
  bool pairs = false;  // fnet side: compute_persistence_pairs (diagrams + their simplices)
};

// glibc returns freed memory at the top of the heap to the system (above 128 KiB) and maps
// large blocks afresh each time; every reuse then pays page faults again, ~24 us per 4 KiB page
// on the paravirtualized machine this was written on, which swamps a sub-millisecond run. A
// long-running service reaches a steady state instead; these settings give it from the start,
// to both sides alike: blocks under 32 MiB come from the heap, and the heap is not trimmed.
void steady_state_malloc() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

enum class Side { fnet, gudhi };

struct Measurement {
  bool ran = false;  // false: skipped
  bool ok = false;
  std::string failure;
  Timing timing;
  long peak_rss_kib = 0;
  std::vector<FrameDiagrams> diagrams;  // one per kind, from the last run
};

void write_diagram(std::FILE* out, const Diagram& d) {
  const std::size_t n = d.size();
  std::fwrite(&n, sizeof n, 1, out);
  std::fwrite(d.data(), sizeof(PersistencePoint), n, out);
}

Diagram read_diagram(std::FILE* in) {
  std::size_t n = 0;
  if (std::fread(&n, sizeof n, 1, in) != 1) throw std::runtime_error("truncated child output");
  Diagram d(n);
  if (std::fread(d.data(), sizeof(PersistencePoint), n, in) != n) throw std::runtime_error("truncated child output");
  return d;
}

// What is timed: fnet from the raw frame (build_network + compute_persistence); GUDHI from the
// normalized edge list fnet built (not timed) through its flag-complex pipeline. Each run takes
// the next of the distinct frames, so that neither side can have its branches learnt by heart.
// A first pass over the frames warms up and writes the diagrams for the comparison.
Measurement measure(Side side, const std::vector<Frame>& frames, const std::vector<ForceKind>& kinds, double budget_s,
                    bool pairs) {
  const ChildRun run = run_in_child([&](std::FILE* out) {
    std::vector<std::vector<ForceNetwork>> nets(frames.size());  // GUDHI's input, prepared untimed
    if (side == Side::gudhi)
      for (std::size_t f = 0; f < frames.size(); ++f)
        for (ForceKind kind : kinds) nets[f].push_back(build_network(frames[f], kind));
    const auto diagrams = [&](std::size_t f, std::size_t k) {
      if (side == Side::fnet && pairs) return compute_persistence_pairs(build_network(frames[f], kinds[k])).diagrams;
      return side == Side::fnet ? compute_persistence(build_network(frames[f], kinds[k]))
                                : testing::gudhi_persistence(frames[f].particle_count, nets[f][k].edges);
    };
    for (std::size_t f = 0; f < frames.size(); ++f)
      for (std::size_t k = 0; k < kinds.size(); ++k) {
        const FrameDiagrams d = diagrams(f, k);
        const std::size_t counts[2] = {d.edges, d.triangles};
        std::fwrite(counts, sizeof counts, 1, out);
        write_diagram(out, d.pd0);
        write_diagram(out, d.pd1);
      }
    std::size_t next = 0;
    std::vector<FrameDiagrams> result(kinds.size());  // a service keeps what it computed
    std::vector<PairedDiagrams> paired(kinds.size());
    const Timing timing = median_time(
        [&] {
          const std::size_t f = next++ % frames.size();
          for (std::size_t k = 0; k < kinds.size(); ++k) {
            if (pairs && side == Side::fnet)
              paired[k] = compute_persistence_pairs(build_network(frames[f], kinds[k]));
            else
              result[k] = diagrams(f, k);
          }
        },
        budget_s);
    std::fwrite(&timing, sizeof timing, 1, out);
  });
  Measurement m;
  m.ran = true;
  m.ok = run.ok;
  m.failure = run.failure;
  m.peak_rss_kib = run.peak_rss_kib;
  if (run.ok) {
    for (std::size_t k = 0; k < frames.size() * kinds.size(); ++k) {
      FrameDiagrams d;
      std::size_t counts[2];
      if (std::fread(counts, sizeof counts, 1, run.output) != 1) throw std::runtime_error("truncated child output");
      d.edges = counts[0], d.triangles = counts[1];
      d.pd0 = read_diagram(run.output);
      d.pd1 = read_diagram(run.output);
      m.diagrams.push_back(std::move(d));
    }
    if (std::fread(&m.timing, sizeof m.timing, 1, run.output) != 1) throw std::runtime_error("truncated child output");
  }
  std::fclose(run.output);
  return m;
}

std::string mib(long kib) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", static_cast<double>(kib) / 1024);
  return s;
}

std::string cell(const Measurement& m, bool memory) {
  if (!m.ran) return "skipped";
  if (!m.ok) return "failed";
  if (memory) return mib(m.peak_rss_kib);
  char s[32];
  std::snprintf(s, sizeof s, "%.3f", m.timing.median_ms);
  return s;
}

// "same" when both sides give the same PD0 and PD1 for every kind measured.
std::string verdict(const Measurement& ours, const Measurement& theirs, std::vector<std::string>& reports) {
  if (!ours.ok || !theirs.ok || !theirs.ran) return "-";
  bool same = true;
  for (std::size_t k = 0; k < ours.diagrams.size(); ++k) {
    const FrameDiagrams& a = ours.diagrams[k];
    const FrameDiagrams& b = theirs.diagrams[k];
    std::string why = testing::diagram_mismatch(a.pd0, b.pd0, 1e-12);
    if (!why.empty()) reports.push_back("PD0: " + why);
    std::string why1 = testing::diagram_mismatch(a.pd1, b.pd1, 1e-12);
    if (!why1.empty()) reports.push_back("PD1: " + why1);
    if (a.triangles != b.triangles) reports.push_back("triangle counts differ");
    same = same && why.empty() && why1.empty() && a.triangles == b.triangles;
  }
  return same ? "same" : "DIFFER";
}

// Small frames are processed so fast that a CPU's branch predictor learns a repeated frame by
// heart and flatters both sides; distinct frames (consecutive seeds) in turn keep it honest.
std::size_t distinct_frames(std::size_t n) { return n <= 20000 ? 16 : 1; }

void run(const Options& opt) {
  std::printf(
      "PD0 + PD1 of synthetic packings (jittered triangular lattice, diameters U[0.8,1.2], exponential forces).\n"
      "fnet ms : build_network(frame, kind) + %s, from the raw frame.\n"
      "GUDHI ms: GUDHI's own flag-complex route on fnet's normalized edges (normalization not timed): vertex\n"
      "          values, Boost graph, Simplex_tree::insert_graph, expansion(2), Persistent_cohomology over Z/2\n"
      "          (min_persistence 0), intervals of dimensions 0 and 1 mapped back to superlevel values.\n"
      "Time    : CPU time of the child's thread (user + sys, so page faults count; time spent preempted by\n"
      "          other processes does not), median over batches of ~1 ms of the runs that fit %.1f s (runs in\n"
      "          parentheses), after one untimed pass. Each run takes the next of F distinct frames, seeds\n"
      "          %llu..%llu+F-1, F = 16 up to N = 20000, else 1. Edges and triangles are the first frame's.\n"
      "Peak RSS: each side in its own forked child, ru_maxrss from wait4, which includes what the child inherits:\n"
      "          the F frames (frames MiB) and the process baseline (idle MiB: a child that does nothing).\n"
      "          GUDHI's includes its input edge lists.\n"
      "PD      : 'same' = PD0 and PD1 equal as multisets (1e-12 relative) on every frame, for the row's kinds.\n"
      "malloc  : %s.\n\n",
      opt.pairs ? "compute_persistence_pairs (with each point's simplices, --pairs)" : "compute_persistence",
      opt.budget_s, static_cast<unsigned long long>(opt.seed), static_cast<unsigned long long>(opt.seed),
      opt.steady_malloc ? "steady state for both sides (mmap threshold 32 MiB, no heap trimming; --steady-malloc=0: "
                          "glibc's defaults)"
                        : "glibc defaults");
  std::printf("%9s %-10s %9s %9s %17s %19s %8s %10s %10s %10s %8s %6s\n", "N", "force", "edges", "triangles",
              "fnet ms (runs)", "GUDHI ms (runs)", "ratio", "fnet MiB", "GUDHI MiB", "frames MiB", "idle MiB", "PD");
  std::vector<std::string> reports;
  for (std::size_t n : opt.sizes) {
    std::vector<Frame> frames;
    std::size_t frame_bytes = 0;
    for (std::size_t f = 0; f < distinct_frames(n); ++f) {
      frames.push_back(testing::synthetic_frame({.particles = n, .seed = opt.seed + f}));
      validate(frames.back());
      frame_bytes +=
          frames.back().particles.size() * sizeof(Particle) + frames.back().contacts.size() * sizeof(Contact);
    }
    const long frames_kib = static_cast<long>(frame_bytes / 1024);
    const long idle_kib = run_in_child([](std::FILE*) {}).peak_rss_kib;
    const bool with_gudhi = n <= opt.gudhi_max;
    const std::vector<std::vector<ForceKind>> rows = {
        {ForceKind::normal}, {ForceKind::tangential}, {ForceKind::normal, ForceKind::tangential}};
    for (const auto& kinds : rows) {
      std::fprintf(stderr, "N=%zu %zu kind(s): fnet...\n", n, kinds.size());
      const Measurement ours = measure(Side::fnet, frames, kinds, opt.budget_s, opt.pairs);
      Measurement theirs;
      if (with_gudhi) {
        std::fprintf(stderr, "N=%zu %zu kind(s): GUDHI...\n", n, kinds.size());
        theirs = measure(Side::gudhi, frames, kinds, opt.budget_s, false);
      }
      std::size_t edges = 0, triangles = 0;
      for (std::size_t k = 0; k < kinds.size() && k < ours.diagrams.size(); ++k)
        edges += ours.diagrams[k].edges, triangles += ours.diagrams[k].triangles;
      const std::size_t before = reports.size();
      const std::string pd = verdict(ours, theirs, reports);
      for (std::size_t r = before; r < reports.size(); ++r) reports[r] = "N=" + std::to_string(n) + ": " + reports[r];
      char ratio[32] = "-";
      if (ours.ok && theirs.ok)
        std::snprintf(ratio, sizeof ratio, "%.1fx", theirs.timing.median_ms / ours.timing.median_ms);
      const auto with_runs = [](const Measurement& m) {
        return m.ok ? cell(m, false) + " (" + std::to_string(m.timing.runs) + ")" : cell(m, false);
      };
      std::printf("%9zu %-10s %9zu %9zu %17s %19s %8s %10s %10s %10s %8s %6s\n", n,
                  kinds.size() == 2 ? "both" : std::string(to_string(kinds[0])).c_str(), edges, triangles,
                  with_runs(ours).c_str(), with_runs(theirs).c_str(), ratio, cell(ours, true).c_str(),
                  cell(theirs, true).c_str(), mib(frames_kib).c_str(), mib(idle_kib).c_str(), pd.c_str());
      std::fflush(stdout);
      if (!ours.ok) reports.push_back("N=" + std::to_string(n) + ": fnet child " + ours.failure);
      if (theirs.ran && !theirs.ok) reports.push_back("N=" + std::to_string(n) + ": GUDHI child " + theirs.failure);
    }
  }
  if (opt.gudhi_max < opt.sizes.back()) std::printf("\nGUDHI skipped above N = %zu (--gudhi-max).\n", opt.gudhi_max);
  for (const std::string& r : reports) std::printf("\n%s", r.c_str());
  if (!reports.empty()) std::printf("\n");
}

std::vector<std::size_t> parse_sizes(const std::string& text) {
  std::vector<std::size_t> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::stoul(item));
  if (sizes.empty()) throw std::invalid_argument("--sizes: empty list");
  return sizes;
}

}  // namespace
}  // namespace fnet::bench

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  fnet::bench::Options opt;
  std::string sizes;
  po::options_description desc("bench_persistence: fnet vs GUDHI, PD0 + PD1 of synthetic packings");
  desc.add_options()("help,h", "this text")("sizes", po::value(&sizes)->default_value("2000,20000,200000,2000000"),
                                            "comma-separated particle counts")(
      "gudhi-max", po::value(&opt.gudhi_max)->default_value(2000000), "skip GUDHI above this many particles")(
      "budget", po::value(&opt.budget_s)->default_value(1.0), "seconds of repeated runs per measurement")(
      "seed", po::value(&opt.seed)->default_value(1), "seed of the synthetic frames")(
      "steady-malloc", po::value(&opt.steady_malloc)->default_value(true), "tune malloc like a long-running service")(
      "pairs", po::bool_switch(&opt.pairs), "time compute_persistence_pairs (diagrams and their simplices) for fnet");
  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, desc), vm);
    po::notify(vm);
    if (vm.count("help")) {
      std::cout << desc << "\n";
      return 0;
    }
    opt.sizes = fnet::bench::parse_sizes(sizes);
    if (opt.steady_malloc) fnet::bench::steady_state_malloc();
    fnet::bench::run(opt);
  } catch (const std::exception& e) {
    std::cerr << "bench_persistence: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
