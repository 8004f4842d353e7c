#include "tests/e2e/planted_fcc_run.hpp"

#include <cstdint>

#include "common/store/run_file.hpp"
#include "tests/support/fcc_packing.hpp"
#include "tests/support/grid_cells.hpp"

namespace fnet::e2e {

Planted3D plant_in_cell(const PlantedCell& where) {
  Planted3D out;
  out.original = testing::fcc_frame({.cells = where.cells});
  out.planted = testing::strengthen(
      out.original, testing::contacts_in_cell(out.original, where.k, where.layer, where.row, where.col, 0.2), 20);
  return out;
}

std::filesystem::path write_run_file_3d(const std::filesystem::path& path, const std::string& run_id,
                                        const Planted3D& run) {
  RunInfo info;
  info.run_id = run_id;
  info.particles = static_cast<std::uint32_t>(run.original.particle_count);
  info.frames = 3;
  info.config_json = "{}";
  RunFileWriter w(path, info);
  const Frame* frames[] = {&run.original, &run.planted, &run.original};
  for (std::uint32_t k = 0; k < 3; ++k) {
    RunFrame f;
    f.header = {run_id, k, 1000 * k, 0.0, 0.74, 12.0};
    f.frame = *frames[k];
    f.frame.label = run_id + " frame " + std::to_string(k);
    w.append(f);
  }
  return path;
}

}  // namespace fnet::e2e
