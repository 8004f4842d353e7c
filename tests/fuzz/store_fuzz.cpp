// An analysis store as fnet-server loads it at start and on server.rescan (read_store), and the
// force networks network.get reads from it (read_network). Input: the HDF5 file.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include <hdf5.h>

#include "common/store/analysis_store.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  // HDF5's free lists unbounded: each open's metadata cache (over 512 KiB, zeroed) is then reused
  // instead of mapped and unmapped by AddressSanitizer's allocator at every open.
  static const bool free_lists = H5set_free_list_limits(-1, -1, -1, -1, -1, -1) >= 0;
  (void)free_lists;
  const auto path = fuzz::write_file("store.h5", {reinterpret_cast<const char*>(data), size});
  try {
    const fnet::StoredRun run = fnet::read_store(path);
    // The networks of the first frames: each is read by opening the store again.
    for (std::size_t k = 0; k < std::min<std::size_t>(run.frames.size(), 3); ++k) {
      try {
        if (const auto network = fnet::read_network(path, run.frames[k].header.index)) fnet::validate(*network);
      } catch (const fnet::FrameError& e) {
        fuzz::require_names(e, {"frame "});
      }
    }
  } catch (const fnet::h5::Error& e) {
    fuzz::require_names(e, {path.string()});
  }
  return 0;
}
