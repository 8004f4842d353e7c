// Writes the diagrams of the frame pair bench_frame_analysis measures (a synthetic packing and the
// frame after it, tests/support/synthetic_frame.hpp) as `fnet-analyze diagram` documents, one per
// frame and force, for the distance benchmarks (bench_distance_exe) and profilers:
//   write_frame_pair_diagrams DIM GRAINS SEED OUT_DIR
// writes OUT_DIR/{a,b}_{normal,tangential}.json.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "common/analysis/run_pipeline.hpp"
#include "common/codec/diagram_json.hpp"
#include "tests/support/synthetic_frame.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: write_frame_pair_diagrams DIM GRAINS SEED OUT_DIR\n";
    return 2;
  }
  const int dimension = std::atoi(argv[1]);
  const std::size_t grains = std::strtoull(argv[2], nullptr, 10);
  const std::uint64_t seed = std::strtoull(argv[3], nullptr, 10);
  const std::filesystem::path dir = argv[4];
  if (dimension != 2 && dimension != 3) {
    std::cerr << "write_frame_pair_diagrams: DIM must be 2 or 3, got " << argv[1] << "\n";
    return 2;
  }
  using namespace fnet;
  auto a = std::make_shared<Frame>(testing::synthetic_frame(testing::disordered_packing(dimension, grains, seed)));
  auto b = std::make_shared<Frame>(testing::next_frame(*a, {.seed = seed}));
  std::filesystem::create_directories(dir);
  for (const auto& [name, frame] : {std::pair{"a", a}, std::pair{"b", b}}) {
    const DiagramOutcome out = DiagramJob{0, frame}.run();
    if (!out.diagrams) {
      std::cerr << "write_frame_pair_diagrams: " << out.reason << "\n";
      return 1;
    }
    for (const ForceKind force : {ForceKind::normal, ForceKind::tangential}) {
      const std::filesystem::path path = dir / (std::string(name) + "_" + std::string(to_string(force)) + ".json");
      std::ofstream file(path);
      file << diagram_document_text((*out.diagrams)[force]);
      if (!file.flush()) {
        std::cerr << path.string() << ": cannot write\n";
        return 1;
      }
    }
  }
  return 0;
}
