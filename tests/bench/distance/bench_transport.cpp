// One Wasserstein distance between the PD1s (or PD0s) of two diagram documents, timed in process,
// with the solver chosen and its work counters: what bench_transport.py runs beside Hera.
//   bench_transport_exe [--q Q] [--delta D] [--solver auto|paths|simplex] [--dim K] [--repeat R] A.json B.json
// Prints one line: seconds (median of repeats) value lower upper pivots pricing_rounds pair_arcs
// augmentations solver.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/distance/wasserstein.hpp"
#include "tests/bench/distance/bench_inputs.hpp"

using namespace fnet;

int main(int argc, char** argv) {
  WassersteinParams params;
  int dim = 1, repeat = 1;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    const bool more = k + 1 < argc;
    if (arg == "--q" && more) {
      params.q = std::atof(argv[++k]);
    } else if (arg == "--delta" && more) {
      params.delta = std::atof(argv[++k]);
    } else if (arg == "--dim" && more) {
      dim = std::atoi(argv[++k]);
    } else if (arg == "--repeat" && more) {
      repeat = std::max(1, std::atoi(argv[++k]));
    } else if (arg == "--solver" && more) {
      const std::string s = argv[++k];
      params.solver = s == "paths"     ? WassersteinSolver::shortest_paths
                      : s == "simplex" ? WassersteinSolver::network_simplex
                                       : WassersteinSolver::automatic;
    } else {
      files.push_back(arg);
    }
  }
  if (files.size() != 2) {
    std::fprintf(stderr,
                 "usage: bench_transport_exe [--q Q] [--delta D] [--solver auto|paths|simplex] [--dim K] "
                 "[--repeat R] A.json B.json\n");
    return 2;
  }
  const Diagram a = bench::load_diagram(files[0], dim), b = bench::load_diagram(files[1], dim);
  std::vector<double> times;
  DistanceResult r;
  WassersteinStats st;
  for (int k = 0; k < repeat; ++k) {
    const auto start = std::chrono::steady_clock::now();
    r = wasserstein_distance(a, b, params, &st);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  std::printf("%.6f %.17g %.17g %.17g %zu %zu %zu %zu %s\n", times[times.size() / 2], r.value, r.lower, r.upper,
              st.pivots, st.pricing_rounds, st.candidate_arcs, st.augmentations,
              st.network_simplex ? "simplex" : "paths");
  return 0;
}
