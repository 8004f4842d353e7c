// All twelve exact distances of frame pairs (d_B, W1, W2 x PD0, PD1, per file pair), timed in
// process (median of repeats), with the Wasserstein solver's work counters.
//   bench_distance [--repeat R] A.json B.json [A2.json B2.json ...]
// Files: fnet-analyze diagram output ({"pd0": [[b, d], ...], "pd1": ...}).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common/distance/bottleneck.hpp"
#include "common/distance/wasserstein.hpp"
#include "tests/bench/distance/bench_inputs.hpp"

using namespace fnet;

int main(int argc, char** argv) {
  const auto [repeat, files] = bench::parse_pair_args(argc, argv, "bench_distance", 5);
  std::printf("%-44s %3s %6s  %-10s %10s %10s %8s %10s %s\n", "pair", "dim", "pts", "metric", "ms", "value", "augment",
              "settled/boxes", "arcs rounds repaired complete");
  for (std::size_t f = 0; f < files.size(); f += 2) {
    double pair_total = 0;
    for (int dim = 0; dim < 2; ++dim) {
      const Diagram a = bench::load_diagram(files[f], dim), b = bench::load_diagram(files[f + 1], dim);
      for (const double q : {0.0, 1.0, 2.0}) {
        std::vector<double> times;
        double value = 0;
        WassersteinStats st;
        for (int r = 0; r < repeat; ++r) {
          const auto start = std::chrono::steady_clock::now();
          value = q == 0 ? bottleneck_distance(a, b).value : wasserstein_distance(a, b, {.q = q}, &st).value;
          times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        std::sort(times.begin(), times.end());
        const double t = times[times.size() / 2];
        pair_total += t;
        const std::string name = bench::pair_name(files[f], files[f + 1]);
        std::printf("%-44s %3d %6zu  %-10s %10.2f %10.6g %8zu %10zu/%zu %zu %zu %zu %d\n", name.c_str(), dim,
                    std::max(a.size(), b.size()),
                    q == 0   ? "bottleneck"
                    : q == 1 ? "W1"
                             : "W2",
                    t * 1e3, value, st.augmentations, st.settled, st.boxes_opened, st.candidate_arcs, st.certify_rounds,
                    st.repaired_rows, st.completed ? 1 : 0);
      }
    }
    std::printf("  six distances of this file pair: %.2f ms\n", pair_total * 1e3);
  }
  return 0;
}
