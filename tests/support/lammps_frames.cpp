#include "tests/support/lammps_frames.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/codec/frame_csv.hpp"

namespace fnet::testing {
namespace {

const std::filesystem::path kRun = std::filesystem::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";

std::filesystem::path frame_file(std::size_t index, const char* table) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%04zu_%s.csv", index, table);
  return kRun / name;
}

}  // namespace

std::size_t lammps_frame_count() {
  std::size_t n = 0;
  while (std::filesystem::exists(frame_file(n, "contacts"))) ++n;
  return n;
}

Frame lammps_frame(std::size_t index) {
  return read_frame_csv(frame_file(index, "contacts"), frame_file(index, "particles"));
}

}  // namespace fnet::testing
