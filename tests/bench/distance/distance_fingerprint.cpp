// Every observable of the diagram distances as hex floats, for diffing two builds of the solvers:
// values and bounds, the Wasserstein solver's work counters and dual certificate (its potentials
// and matching, hashed bit for bit), the bottleneck's value and matching. A change meant to keep
// the solvers' arithmetic (a reorganisation) must leave this output identical.
//   distance_fingerprint [--large] [A.json B.json ...]
// Inputs: the given diagram pairs (both dimensions), then seeded random pairs: ties, points on the
// diagonal, a common death line, never-dying classes, a huge dynamic range, empty sides; --large
// adds pairs past the staged solve's size (a few minutes).
#include <bit>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/distance/bottleneck.hpp"
#include "common/distance/diagonal_flow.hpp"
#include "common/distance/wasserstein.hpp"
#include "tests/bench/distance/bench_inputs.hpp"

using namespace fnet;

namespace {

struct Hash {  // FNV-1a over 64-bit words
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void add(std::uint64_t x) {
    for (int k = 0; k < 8; ++k) h = (h ^ ((x >> (8 * k)) & 0xff)) * 0x100000001b3ULL;
  }
  void add(double x) { add(std::bit_cast<std::uint64_t>(x)); }
};

std::uint64_t matching_hash(const DiagramMatching& m) {
  Hash h;
  for (const MatchedPair& p : m.pairs) {
    h.add(static_cast<std::uint64_t>(p.a)), h.add(static_cast<std::uint64_t>(p.b)), h.add(p.length);
  }
  h.add(static_cast<std::uint64_t>(m.longest));
  return h.h;
}

void print_result(const char* what, const DistanceResult& r) {
  std::printf("  %s value %a lower %a upper %a exact %d infinite %d\n", what, r.value, r.lower, r.upper,
              r.exact ? 1 : 0, r.infinite ? 1 : 0);
}

// full: every convention and exponent; otherwise floor with q = 1, 2 (the large pairs).
void distances(const Diagram& a, const Diagram& b, bool full) {
  for (const EssentialConvention c :
       {EssentialConvention::floor, EssentialConvention::sentinel, EssentialConvention::separate}) {
    if (!full && c != EssentialConvention::floor) continue;
    std::printf(" convention %s\n", std::string(to_string(c)).c_str());
    for (const double rel : {0.0, 0.01}) {
      DiagramMatching m;
      const DistanceResult r = bottleneck_distance(a, b, {.essential = c, .relative_error = rel}, &m);
      std::printf("  bottleneck rel %a matching %016" PRIx64 "\n", rel, matching_hash(m));
      print_result("bottleneck", r);
    }
    for (const double q : {1.0, 2.0, 1.5, 3.0}) {
      for (const double delta : {0.0, 0.1, 0.5}) {
        if ((c != EssentialConvention::floor && delta > 0 && q > 2) || (!full && (q > 2 || q != std::floor(q))))
          continue;
        WassersteinStats st;
        DiagramMatching m;
        const DistanceResult r = wasserstein_distance(a, b, {.q = q, .essential = c, .delta = delta}, &st, &m);
        std::printf("  W q %a delta %a matching %016" PRIx64 "\n", q, delta, matching_hash(m));
        print_result("W", r);
        std::printf(
            "  stats augment %zu settled %zu boxes %zu arcs %zu rounds %zu repaired %zu complete %d line %d "
            "dual %a\n",
            st.augmentations, st.settled, st.boxes_opened, st.candidate_arcs, st.certify_rounds, st.repaired_rows,
            st.completed ? 1 : 0, st.line_start ? 1 : 0, st.dual_lower);
      }
    }
  }
}

void flow_state(const char* how, const DiagonalFlow& f, std::size_t n, std::size_t m) {
  Hash pi, mates;
  for (const double p : f.potentials()) pi.add(p);
  for (std::uint32_t i = 0; i < n; ++i) mates.add(static_cast<std::uint64_t>(f.mate_of_a(i)));
  for (std::uint32_t j = 0; j < m; ++j) mates.add(static_cast<std::uint64_t>(f.mate_of_b(j)));
  std::printf("  flow %s primal %a dual %a potentials %016" PRIx64 " mates %016" PRIx64
              " augment %zu settled %zu boxes %zu arcs %zu rounds %zu repaired %zu complete %d line %d\n",
              how, f.primal_cost(), f.dual_bound(), pi.h, mates.h, f.augmentations(), f.settled(), f.boxes_opened(),
              f.candidate_arcs(), f.certify_rounds(), f.repaired_rows(), f.finished_on_complete_graph() ? 1 : 0,
              f.started_on_line() ? 1 : 0);
}

// The flow itself on the diagrams' finite points (as the floor convention sees them).
void flows(const Diagram& a, const Diagram& b) {
  std::vector<PlanePoint> pa, pb;
  for (const PersistencePoint p : a) pa.push_back({p.birth, p.death == kNeverDies ? 0.0 : p.death});
  for (const PersistencePoint p : b) pb.push_back({p.birth, p.death == kNeverDies ? 0.0 : p.death});
  if (pa.empty() || pb.empty()) return;
  for (const double q : {1.0, 2.0, 2.5}) {
    std::printf(" flow q %a\n", q);
    const ArcPower power(q);
    for (const double ratio : {1.0, 1.05, 1.5}) {
      DiagonalFlow f(pa, pb, power);
      f.solve(ratio);
      char how[64];
      std::snprintf(how, sizeof how, "solve(%a)", ratio);
      flow_state(how, f, pa.size(), pb.size());
    }
    DiagonalFlow f(pa, pb, power);
    f.solve_complete();
    flow_state("solve_complete", f, pa.size(), pb.size());
  }
}

// small: the flow itself too, and every convention and exponent.
void run(const std::string& name, const Diagram& a, const Diagram& b, bool small = true) {
  std::printf("case %s sizes %zu %zu\n", name.c_str(), a.size(), b.size());
  distances(a, b, small);
  if (small) flows(a, b);
}

// Births in [0, top), deaths below; `line_share` of them on death 0 (never-dying under floor when
// `never` is set), a tenth duplicated, some on the diagonal; B a perturbed copy of A.
void random_pair(std::mt19937_64& rng, std::size_t size, double top, double line_share, double jitter, bool never,
                 Diagram& a, Diagram& b) {
  std::uniform_real_distribution<double> unit(0, 1);
  a.clear(), b.clear();
  for (std::size_t k = 0; k < size; ++k) {
    const double birth = top * unit(rng);
    double death = unit(rng) < line_share ? (never && unit(rng) < 0.5 ? kNeverDies : 0.0) : birth * unit(rng);
    if (unit(rng) < 0.03) death = birth;  // on the diagonal
    a.push_back({birth, death});
    if (unit(rng) < 0.1) a.push_back({birth, death});  // a tie
  }
  for (const PersistencePoint p : a) {
    if (unit(rng) < 0.03) continue;
    double birth = p.birth + jitter * top * (unit(rng) - 0.5);
    double death = p.death == kNeverDies || p.death == 0 ? p.death : p.death + jitter * top * (unit(rng) - 0.5);
    if (birth < 0) birth = 0;
    if (death != kNeverDies && death > birth) death = birth;
    b.push_back({birth, death});
  }
  for (std::size_t k = 0; k < size / 30; ++k) {
    const double mid = top * unit(rng);
    b.push_back({mid + jitter * top * unit(rng), mid});
  }
}

// Coordinates log-uniform over [1e-150, 1e150].
void wide_pair(std::mt19937_64& rng, std::size_t size, Diagram& a, Diagram& b) {
  std::uniform_real_distribution<double> unit(0, 1);
  const auto wide = [&] { return std::pow(10.0, 300 * unit(rng) - 150); };
  a.clear(), b.clear();
  for (std::size_t k = 0; k < size; ++k) {
    const double birth = wide();
    a.push_back({birth, unit(rng) < 0.5 ? 0.0 : birth * unit(rng)});
    const double birth_b = unit(rng) < 0.5 ? birth * (1 + 1e-3 * unit(rng)) : wide();
    b.push_back({birth_b, unit(rng) < 0.5 ? 0.0 : birth_b * unit(rng)});
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool large = false;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--large") {
      large = true;
    } else {
      files.push_back(arg);
    }
  }
  if (files.size() % 2) {
    std::fprintf(stderr, "usage: distance_fingerprint [--large] [A.json B.json ...]\n");
    return 2;
  }
  for (std::size_t f = 0; f < files.size(); f += 2)
    for (int dim = 0; dim < 2; ++dim)
      run(bench::pair_name(files[f], files[f + 1]) + " pd" + std::to_string(dim), bench::load_diagram(files[f], dim),
          bench::load_diagram(files[f + 1], dim));

  std::mt19937_64 rng(20240520);
  Diagram a, b;
  run("empty both", a, b);
  a = {{1, 0}, {2, 0.5}, {3, kNeverDies}};
  run("empty b", a, b);
  run("empty a", b, a);
  run("all on the diagonal", {{1, 1}, {2, 2}}, {{3, 3}});
  run("one each", {{1, 0}}, {{1.5, 0.25}});
  run("identical", {{1, 0}, {2, 0}, {2, 0}, {3, 1}}, {{1, 0}, {2, 0}, {2, 0}, {3, 1}});
  run("all ties", Diagram(40, {1, 0}), Diagram(37, {1, 0}));
  run("zeros", Diagram(20, {0, 0}), {{0, 0}, {1e-300, 0}, {0.5, 0}});
  for (const std::size_t size : {5u, 30u, 200u, 1000u, 3000u}) {
    for (const double line_share : {0.0, 0.5, 0.9}) {
      for (const double jitter : {0.0, 1e-3, 0.05}) {
        random_pair(rng, size, 10, line_share, jitter, true, a, b);
        char name[96];
        std::snprintf(name, sizeof name, "random %zu line %.1f jitter %g", size, line_share, jitter);
        run(name, a, b, size <= 1000);
      }
    }
  }
  for (const std::size_t size : {10u, 300u, 2000u}) {
    wide_pair(rng, size, a, b);
    run("wide range " + std::to_string(size), a, b);
  }
  // Integer coordinates on a small grid: many equal costs.
  {
    std::uniform_int_distribution<int> grid(0, 6);
    a.clear(), b.clear();
    for (int k = 0; k < 400; ++k) {
      const int x = grid(rng), y = grid(rng);
      a.push_back({double(std::max(x, y)), double(std::min(x, y))});
      const int u = grid(rng), v = grid(rng);
      b.push_back({double(std::max(u, v)), double(std::min(u, v))});
    }
    run("grid 400", a, b);
  }
  if (large) {
    for (const double line_share : {0.95, 0.0}) {
      random_pair(rng, 12000, 1, line_share, 2e-3, false, a, b);
      run("large 12000 line " + std::to_string(line_share), a, b, false);
    }
  }
  return 0;
}
