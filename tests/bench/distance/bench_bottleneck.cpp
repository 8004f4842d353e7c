// The exact bottleneck distance of diagram pairs, timed in process (median of repeats).
//   bench_bottleneck [--repeat R] [--dim D] A.json B.json [A2.json B2.json ...]
// Files: fnet-analyze diagram output ({"pd0": [[b, d], ...], "pd1": ...}); one line per pair:
// points, milliseconds, value (17 digits).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/distance/bottleneck.hpp"
#include "tests/bench/distance/bench_inputs.hpp"

using namespace fnet;

int main(int argc, char** argv) {
  int repeat = 3, dim = 1;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--repeat" && k + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++k]));
    else if (arg == "--dim" && k + 1 < argc)
      dim = std::atoi(argv[++k]);
    else
      files.push_back(arg);
  }
  if (files.empty() || files.size() % 2 || (dim != 0 && dim != 1)) {
    std::fprintf(stderr, "usage: bench_bottleneck [--repeat R] [--dim 0|1] A.json B.json [...]\n");
    return 2;
  }
  for (std::size_t f = 0; f < files.size(); f += 2) {
    const Diagram a = bench::load_diagram(files[f], dim), b = bench::load_diagram(files[f + 1], dim);
    std::vector<double> times;
    double value = 0;
    for (int r = 0; r < repeat; ++r) {
      const auto start = std::chrono::steady_clock::now();
      value = bottleneck_distance(a, b).value;
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    std::printf("%zu %.3f %.17g\n", std::max(a.size(), b.size()), times[times.size() / 2] * 1e3, value);
  }
  return 0;
}
