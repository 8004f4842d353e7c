// The whole analysis of one frame as the run pipeline does it, against N, in 2D and 3D: the
// diagrams of the new frame (DiagramJob: validation, PD0 and PD1 of the normal and tangential
// networks) and its twelve distances to the previous frame (DistanceJob: bottleneck, W1, W2 x PD0,
// PD1 x normal, tangential). Frames: synthetic packings and the frame after each
// (tests/support/synthetic_frame.hpp). Each size runs in a forked child so that its peak memory
// (ru_maxrss: the two frames, their diagrams and the solvers' working memory) is its own. Where the
// frame has at most --anchor-max-contacts contacts, the same frame pair goes to GUDHI and Hera
// through Python (anchor_frame_analysis.py), and both sides' diagrams and distances are compared.
//   bench_frame_analysis [--grains2d N,...] [--grains3d N,...] [--anchor-max-contacts C] [--seed S]
//                        [--python PATH] [--no-anchor] [--one-thread] [--limit S] [--delta D]
#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "common/analysis/run_pipeline.hpp"
#include "common/codec/diagram_json.hpp"
#include "tests/bench/persistence/child_process.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/diagram_match.hpp"
#include "tests/support/synthetic_frame.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::bench {
namespace {

constexpr std::size_t kSeries = kStoredSeries.size();
constexpr double kHeraDelta = 0.01;  // anchor_frame_analysis.py's relative error

// What one size's child reports (written raw to the parent).
struct FrameFigures {
  std::size_t grains = 0, contacts = 0;
  std::size_t pd0[2] = {}, pd1[2] = {};  // frame B, normal and tangential
  double diagram_s = 0, distance_s = 0;  // DiagramJob::run(), DistanceJob::run() on one thread
  double total1_s = 0, total2_s = 0;     // wall time of both jobs on one and on two threads (0: not run)
  bool same2 = true;                     // the two-thread values equal the one-thread ones bit for bit
  std::array<double, kSeries> value{}, seconds{};
  std::array<bool, kSeries> done{};  // false: over the time limit, or not tried (see Options)
  // With a relative error delta > 0 (Options::delta): the same, and both jobs on two threads.
  std::array<double, kSeries> approx_value{}, approx_seconds{};
  std::array<bool, kSeries> approx_done{};
  double approx_total2_s = 0;
  long distance_peak_kib = 0;  // the largest of the distances' children
  bool complete() const {
    return std::all_of(done.begin(), done.end(), [](bool d) { return d; });
  }
};

// One distance of the pair, as step_distances() computes it, in a child of its own: stopped after
// limit_s seconds of CPU time.
struct OneDistance {
  bool done = false;
  double value = 0, seconds = 0;
  long peak_kib = 0;
};

struct Options {
  std::vector<std::size_t> grains2d, grains3d;
  std::size_t anchor_max_contacts = 30000;
  std::uint64_t seed = 1;
  std::string python = "/usr/bin/python3";
  bool anchor = true;
  bool two_threads = true;
  unsigned limit_s = 60;  // one distance's CPU time limit; a distance over it is not tried at larger N
  double delta = 0;       // > 0: every distance also within this relative error, against the exact value
};

std::vector<std::size_t> parse_list(const std::string& text) {
  std::vector<std::size_t> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(static_cast<std::size_t>(std::stod(item)));
  return out;
}

void write_csvs(const Frame& f, const std::filesystem::path& contacts, const std::filesystem::path& particles) {
  std::ofstream c(contacts), p(particles);
  c.precision(17);
  p.precision(17);
  c << "i,j,fn,ft\n";
  for (const Contact& k : f.contacts) c << k.i << ',' << k.j << ',' << k.fn << ',' << k.ft << '\n';
  p << "id,x,y,z,r\n";
  for (std::size_t i = 0; i < f.particles.size(); ++i) {
    const Particle& q = f.particles[i];
    p << i << ',' << q.x << ',' << q.y << ',' << q.z << ',' << q.r << '\n';
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// On a machine shared with other work the one-thread figures are CPU time, which the neighbours
// do not inflate; the two-thread figure can only be wall time.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// Frame A (already analyzed when B arrives, as in a run) and B; times B's diagram job and the
// distances of try_series, then both jobs on two threads. When B has at most
// `anchor_max_contacts`, writes both frames as CSV and B's diagrams as documents to `dir` for the
// anchor.
FrameFigures measure(int dimension, std::size_t grains, std::uint64_t seed, const std::filesystem::path& dir,
                     std::size_t anchor_max_contacts, bool two_threads, const std::array<bool, kSeries>& try_series,
                     unsigned limit_s, double delta) {
  auto a = std::make_shared<Frame>(testing::synthetic_frame(testing::disordered_packing(dimension, grains, seed)));
  auto b = std::make_shared<Frame>(testing::next_frame(*a, {.seed = seed}));
  a->label = "frame 0", b->label = "frame 1";
  const DiagramOutcome before = DiagramJob{0, a}.run();
  if (!before.diagrams) throw std::runtime_error(before.reason);

  FrameFigures out;
  out.grains = grains;
  out.contacts = b->contacts.size();
  const double cpu = thread_cpu_seconds();
  DiagramOutcome after = DiagramJob{1, b}.run();
  out.diagram_s = thread_cpu_seconds() - cpu;
  if (!after.diagrams) throw std::runtime_error(after.reason);
  const auto previous = std::make_shared<const FrameDiagramSet>(*before.diagrams);
  const auto current = std::make_shared<const FrameDiagramSet>(std::move(*after.diagrams));
  for (int k = 0; k < 2; ++k) {
    const FrameDiagrams& fd = (*current)[kForces[static_cast<std::size_t>(k)]];
    out.pd0[k] = fd.pd0.size(), out.pd1[k] = fd.pd1.size();
  }
  // The distances one by one (as step_distances() takes them), each in a child of this child, so
  // that one over the limit costs only itself.
  const auto one_distance = [&](const StoredSeries& s, double error) {
    const ChildRun child = run_in_child([&](std::FILE* file) {
      const rlimit budget{limit_s, limit_s + 1};  // SIGXCPU past limit_s seconds of CPU time ends the child
      setrlimit(RLIMIT_CPU, &budget);
      OneDistance one;
      const double start = thread_cpu_seconds();
      one.value = diagram_distance(diagram_of(*previous, s.force, s.dim), diagram_of(*current, s.force, s.dim),
                                   distance_metric(s.metric), EssentialConvention::floor, error)
                      .value;
      one.seconds = thread_cpu_seconds() - start;
      one.done = true;
      std::fwrite(&one, sizeof one, 1, file);
    });
    OneDistance one;
    if (!child.ok || std::fread(&one, sizeof one, 1, child.output) != 1) one.done = false;
    std::fclose(child.output);
    one.peak_kib = child.peak_rss_kib;
    return one;
  };
  for (std::size_t k = 0; k < kSeries; ++k) {
    if (try_series[k]) {
      const OneDistance one = one_distance(kStoredSeries[k], 0);
      out.done[k] = one.done, out.value[k] = one.value, out.seconds[k] = one.seconds;
      out.distance_peak_kib = std::max(out.distance_peak_kib, one.peak_kib);
    }
    if (delta > 0) {
      const OneDistance one = one_distance(kStoredSeries[k], delta);
      out.approx_done[k] = one.done, out.approx_value[k] = one.value, out.approx_seconds[k] = one.seconds;
    }
  }
  double sum = 0;
  for (const double t : out.seconds) sum += t;
  out.distance_s = sum;
  // The pipeline's own jobs on two threads, where the distances all finished within the limit.
  // One thread then two, back to back, so that both wall times see the same neighbours.
  if (two_threads && out.complete() && out.diagram_s + sum <= limit_s) {
    for (const int threads : {1, 2}) {
      const auto start = std::chrono::steady_clock::now();
      const DiagramOutcome again = DiagramJob{1, b, threads}.run();
      const auto diagrams = std::make_shared<const FrameDiagramSet>(std::move(*again.diagrams));
      const DistanceOutcome d = DistanceJob{1, previous, diagrams, EssentialConvention::floor, threads}.run();
      (threads == 1 ? out.total1_s : out.total2_s) = seconds_since(start);
      out.same2 = out.same2 && std::memcmp(d.distances.value.data(), out.value.data(), sizeof(double) * kSeries) == 0;
    }
  }
  double approx_sum = 0;
  for (const double t : out.approx_seconds) approx_sum += t;
  const bool approx_complete = std::all_of(out.approx_done.begin(), out.approx_done.end(), [](bool d) { return d; });
  if (delta > 0 && two_threads && approx_complete && out.diagram_s + approx_sum <= limit_s) {
    const auto start = std::chrono::steady_clock::now();
    const DiagramOutcome again = DiagramJob{1, b, 2}.run();
    const auto diagrams = std::make_shared<const FrameDiagramSet>(std::move(*again.diagrams));
    DistanceJob{1, previous, diagrams, EssentialConvention::floor, 2, delta}.run();
    out.approx_total2_s = seconds_since(start);
  }
  if (out.contacts <= anchor_max_contacts) {
    write_csvs(*a, dir / "a_contacts.csv", dir / "a_particles.csv");
    write_csvs(*b, dir / "b_contacts.csv", dir / "b_particles.csv");
    for (const ForceKind force : kForces)
      std::ofstream(dir / ("ours_" + std::string(to_string(force)) + ".json"))
          << diagram_document_text((*current)[force]);
  }
  return out;
}

struct AnchorFigures {
  bool ran = false;
  double diagram_s = 0;
  std::array<double, kSeries> value{}, seconds{};
  std::array<std::string, kSeries> tool;
  std::string diagrams_same;  // "same" or what differs
  double worst_hera = 0;      // largest |hera / fnet - 1| over Hera's distances
  double worst_exact = 0;     // largest |gudhi / fnet - 1| over GUDHI's exact bottlenecks
  bool agree = true;          // every value within its tool's stated error
};

AnchorFigures run_anchor(const Options& opt, const std::filesystem::path& dir) {
  const testing::ProcessResult r =
      testing::run_process(opt.python,
                           {FNET_ANCHOR_SCRIPT, (dir / "a_contacts.csv").string(), (dir / "a_particles.csv").string(),
                            (dir / "b_contacts.csv").string(), (dir / "b_particles.csv").string(), dir.string()},
                           dir);
  if (r.exit_code != 0) throw std::runtime_error("anchor failed: " + r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  AnchorFigures out;
  out.ran = true;
  out.diagram_s = j.at("diagram_seconds").get<double>();
  for (const nlohmann::json& d : j.at("distances")) {
    const std::optional<StoredSeries> s = parse_series_key(d.at("key").get<std::string>());
    if (!s) throw std::runtime_error("anchor: unknown key " + d.at("key").dump());
    const std::size_t k = stored_series_index(s->metric, s->dim, s->force);
    out.value[k] = d.at("value").get<double>();
    out.seconds[k] = d.at("seconds").get<double>();
    out.tool[k] = d.at("tool").get<std::string>();
  }
  out.diagrams_same = "same";
  for (const ForceKind force : kForces) {
    const std::string name(to_string(force));
    const auto load = [&](const std::string& file) {
      std::ifstream in(dir / file);
      return nlohmann::json::parse(in);
    };
    const nlohmann::json ours = load("ours_" + name + ".json"), theirs = load("anchor_" + name + ".json");
    for (int dim = 0; dim < 2; ++dim) {
      const std::string why = testing::diagram_mismatch(diagram_from_json(ours.at(diagram_key(dim))),
                                                        diagram_from_json(theirs.at(diagram_key(dim))), 1e-12);
      if (!why.empty()) out.diagrams_same = name + " " + diagram_key(dim) + ": " + why;
    }
  }
  return out;
}

// Hera's values are those of a matching, within a factor 1 + delta of the optimum; GUDHI's exact
// bottleneck equals ours up to the rounding of the normalization (numpy's mean against ours).
void compare(const std::array<double, kSeries>& ours, AnchorFigures& anchor) {
  for (std::size_t k = 0; k < kSeries; ++k) {
    const double v = ours[k], h = anchor.value[k];
    const double rel = v == 0 ? (h == 0 ? 0 : INFINITY) : h / v - 1;
    if (anchor.tool[k] == "gudhi exact") {
      anchor.worst_exact = std::max(anchor.worst_exact, std::fabs(rel));
      anchor.agree = anchor.agree && std::fabs(rel) <= 1e-12;
    } else {
      anchor.worst_hera = std::max(anchor.worst_hera, std::fabs(rel));
      anchor.agree = anchor.agree && rel >= -kHeraDelta - 1e-12 && rel <= kHeraDelta + 1e-12;
    }
  }
}

// A metric's four distances: their CPU time, or a lower bound on it (">") when some were over the
// limit or not tried.
std::string metric_cell(const FrameFigures& f, std::optional<Metric> metric, double extra_s, unsigned limit_s) {
  double sum = extra_s;
  bool all = true;
  for (std::size_t k = 0; k < kSeries; ++k) {
    if (metric && kStoredSeries[k].metric != *metric) continue;
    sum += f.done[k] ? f.seconds[k] : limit_s;
    all = all && f.done[k];
  }
  char cell[32];
  std::snprintf(cell, sizeof cell, all ? "%.1f" : ">%.0f", sum * 1e3);
  return cell;
}

void print_header() {
  std::printf("%3s %8s %9s %13s %13s %8s %9s %9s %8s %9s %9s %9s %8s | %9s %9s %9s %9s %7s %s\n", "dim", "grains",
              "contacts", "PD0 n/t", "PD1 n/t", "diag ms", "W1 ms", "W2 ms", "dB ms", "total ms", "1thr wall",
              "2thr wall", "peak MiB", "anchor ms", "diag ms", "dist ms", "ratio", "|rel|", "check");
}

void print_row(int dim, const FrameFigures& f, long peak_kib, const AnchorFigures& a, unsigned limit_s) {
  const std::string pd0 = std::to_string(f.pd0[0]) + "/" + std::to_string(f.pd0[1]),
                    pd1 = std::to_string(f.pd1[0]) + "/" + std::to_string(f.pd1[1]);
  char one[32] = "-", two[32] = "-";
  if (f.total1_s > 0) std::snprintf(one, sizeof one, "%.1f", f.total1_s * 1e3);
  if (f.total2_s > 0) std::snprintf(two, sizeof two, "%.1f%s", f.total2_s * 1e3, f.same2 ? "" : "!");
  std::printf(
      "%3d %8zu %9zu %13s %13s %8.1f %9s %9s %8s %9s %9s %9s %8.1f |", dim, f.grains, f.contacts, pd0.c_str(),
      pd1.c_str(), f.diagram_s * 1e3, metric_cell(f, Metric::wasserstein1, 0, limit_s).c_str(),
      metric_cell(f, Metric::wasserstein2, 0, limit_s).c_str(), metric_cell(f, Metric::bottleneck, 0, limit_s).c_str(),
      metric_cell(f, std::nullopt, f.diagram_s, limit_s).c_str(), one, two, static_cast<double>(peak_kib) / 1024);
  if (!a.ran) {
    std::printf(" %9s\n", "-");
    return;
  }
  double anchor_dist = 0;
  for (const double s : a.seconds) anchor_dist += s;
  const double anchor_total = a.diagram_s + anchor_dist;
  std::printf(" %9.1f %9.1f %9.1f %8.1fx %7.1e %s", anchor_total * 1e3, a.diagram_s * 1e3, anchor_dist * 1e3,
              anchor_total / (f.diagram_s + f.distance_s), std::max(a.worst_hera, a.worst_exact),
              a.agree ? "agree" : "DISAGREE");
  std::printf(" PD %s\n", a.diagrams_same.c_str());
}

// Each distance's CPU time (ms; ">limit" when over it, "-" when not tried), after the table.
void print_each(const std::vector<std::pair<int, FrameFigures>>& rows, unsigned limit_s) {
  std::printf(
      "\neach distance, CPU ms (one thread; '>%u000': over the limit; '-': not tried after a smaller frame "
      "went over it)\n%3s %8s",
      limit_s, "dim", "grains");
  for (const StoredSeries& s : kStoredSeries) std::printf(" %26s", series_key(s).c_str());
  std::printf("\n");
  std::array<bool, kSeries> tried{};
  tried.fill(true);
  int last_dim = 0;
  for (const auto& [dim, f] : rows) {
    if (dim != last_dim) tried.fill(true), last_dim = dim;
    std::printf("%3d %8zu", dim, f.grains);
    for (std::size_t k = 0; k < kSeries; ++k) {
      char cell[32];
      if (f.done[k])
        std::snprintf(cell, sizeof cell, "%.1f", f.seconds[k] * 1e3);
      else
        std::snprintf(cell, sizeof cell, tried[k] ? ">%u000" : "-", limit_s);
      tried[k] = f.done[k];
      std::printf(" %26s", cell);
    }
    std::printf("\n");
  }
}

// With a relative error: each metric's CPU time and the largest error measured against the exact
// value (where the exact value was computed within the limit).
void print_approx(const std::vector<std::pair<int, FrameFigures>>& rows, double delta, unsigned limit_s) {
  std::printf(
      "\nrelative error delta = %g: CPU ms of each metric's 4 distances (one thread), largest measured error "
      "(value / exact - 1), 2thr wall: both jobs on two threads\n",
      delta);
  std::printf("%3s %8s %10s %10s %10s %10s %10s %10s %10s %10s\n", "dim", "grains", "W1 ms", "W1 err", "W2 ms",
              "W2 err", "dB ms", "dB err", "total ms", "2thr wall");
  for (const auto& [dim, f] : rows) {
    std::printf("%3d %8zu", dim, f.grains);
    double total = f.diagram_s;
    bool all = true;
    for (const Metric metric : {Metric::wasserstein1, Metric::wasserstein2, Metric::bottleneck}) {
      double sum = 0, err = 0;
      bool done = true, compared = false;
      for (std::size_t k = 0; k < kSeries; ++k) {
        if (kStoredSeries[k].metric != metric) continue;
        sum += f.approx_done[k] ? f.approx_seconds[k] : limit_s;
        done = done && f.approx_done[k];
        if (f.approx_done[k] && f.done[k] && f.value[k] > 0) {
          err = std::max(err, f.approx_value[k] / f.value[k] - 1);
          compared = true;
        }
      }
      total += sum;
      all = all && done;
      char time[32], error[32] = "-";
      std::snprintf(time, sizeof time, done ? "%.1f" : ">%.0f", sum * 1e3);
      if (compared) std::snprintf(error, sizeof error, "%.2e", err);
      std::printf(" %10s %10s", time, error);
    }
    char total_cell[32], two[32] = "-";
    std::snprintf(total_cell, sizeof total_cell, all ? "%.1f" : ">%.0f", total * 1e3);
    if (f.approx_total2_s > 0) std::snprintf(two, sizeof two, "%.1f", f.approx_total2_s * 1e3);
    std::printf(" %10s %10s\n", total_cell, two);
  }
}

int run(const Options& opt) {
  // As in bench_persistence: large blocks from the heap, never trimmed (a service's steady state).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  std::printf(
      "frame pair: disordered synthetic packing (seed %llu) and the frame after it. One thread, CPU time:\n"
      "the new frame's DiagramJob (diag), its distances' W1, W2 and bottleneck (dB: each the sum of 4),\n"
      "total = diag + distances; 1thr/2thr wall: wall time of both jobs with threads = 1, then 2 (run where\n"
      "the total fits the limit; '!': a value differs from the one-thread run's); '>': some distances\n"
      "over the limit of %u CPU s, counted at it; peak: ru_maxrss of the size's child or its distances'\n"
      "children; anchor: GUDHI diagrams + Hera W1/W2 (delta %g) + GUDHI exact bottleneck (Hera above 5000\n"
      "points), CPU time\n",
      static_cast<unsigned long long>(opt.seed), opt.limit_s, kHeraDelta);
  print_header();
  bool all_agree = true, all_same2 = true;
  std::vector<std::pair<int, FrameFigures>> rows;
  for (const int dim : {2, 3}) {
    std::array<bool, kSeries> try_series{};
    try_series.fill(true);
    for (const std::size_t grains : dim == 2 ? opt.grains2d : opt.grains3d) {
      testing::TempDir dir;
      const std::filesystem::path path = dir.path();
      // The frame's size is known once it is made: the child writes the anchor's files.
      const std::size_t anchor_max = opt.anchor ? opt.anchor_max_contacts : 0;
      const ChildRun child = run_in_child([&](std::FILE* out) {
        const FrameFigures f =
            measure(dim, grains, opt.seed, path, anchor_max, opt.two_threads, try_series, opt.limit_s, opt.delta);
        std::fwrite(&f, sizeof f, 1, out);
      });
      FrameFigures f;
      const bool read = child.ok && std::fread(&f, sizeof f, 1, child.output) == 1;
      std::fclose(child.output);
      if (!read) {
        std::printf("%3d %8zu  not measured: %s\n", dim, grains, child.failure.c_str());
        continue;
      }
      try_series = f.done;  // a distance over the limit is not tried on larger frames
      AnchorFigures anchor;
      if (f.contacts <= anchor_max && f.complete()) {
        anchor = run_anchor(opt, path);
        compare(f.value, anchor);
        all_agree = all_agree && anchor.agree && anchor.diagrams_same == "same";
      }
      all_same2 = all_same2 && f.same2;
      print_row(dim, f, std::max(child.peak_rss_kib, f.distance_peak_kib), anchor, opt.limit_s);
      rows.emplace_back(dim, f);
      std::fflush(stdout);
    }
  }
  print_each(rows, opt.limit_s);
  if (opt.delta > 0) print_approx(rows, opt.delta, opt.limit_s);
  std::printf("anchor check: %s\n", all_agree ? "every value agrees" : "DISAGREEMENT (see rows)");
  if (!all_same2) std::printf("two threads: VALUES DIFFER from one thread's (rows marked '!')\n");
  return all_agree && all_same2 ? 0 : 1;
}

}  // namespace
}  // namespace fnet::bench

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  fnet::bench::Options opt;
  std::string g2 = "500,5000,50000,100000,480000", g3 = "330,3300,33000,100000,330000";
  po::options_description desc("bench_frame_analysis");
  desc.add_options()("help", "this text")("grains2d", po::value(&g2), "2D sizes (grains), comma-separated")(
      "grains3d", po::value(&g3), "3D sizes (grains), comma-separated")(
      "anchor-max-contacts", po::value(&opt.anchor_max_contacts), "largest frame given to the anchor")(
      "seed", po::value(&opt.seed), "seed of the synthetic packings")(
      "python", po::value(&opt.python), "Python with gudhi")("no-anchor", po::bool_switch(), "skip GUDHI and Hera")(
      "one-thread", po::bool_switch(), "skip the two-thread run")("limit", po::value(&opt.limit_s),
                                                                  "seconds one distance may take (default 60)");
  po::variables_map vm;
  po::store(po::parse_command_line(argc, argv, desc), vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << desc;
    return 0;
  }
  opt.anchor = !vm["no-anchor"].as<bool>();
  opt.two_threads = !vm["one-thread"].as<bool>();
  opt.grains2d = fnet::bench::parse_list(g2);
  opt.grains3d = fnet::bench::parse_list(g3);
  return fnet::bench::run(opt);
}
