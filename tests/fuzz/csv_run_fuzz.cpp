// A CSV run folder as fnet-analyze store --csv-dir reads it (fnet-simd --export-csv writes it): its
// index, then each frame's CSV files, each frame checked as the analysis checks it. Input: index.csv
// [@@@@ frame_0000_contacts.csv [@@@@ frame_0000_particles.csv [@@@@ frame_0001_contacts.csv ...]]].
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "common/codec/frame_csv.hpp"
#include "server/sources/source_kinds.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto files = fuzz::input_files(data, size);
  fuzz::clear_scratch();
  fuzz::write_file("index.csv", files[0]);
  for (std::size_t k = 1; k < files.size(); ++k) {
    char name[48];
    std::snprintf(name, sizeof name, "frame_%04zu_%s.csv", (k - 1) / 2, k % 2 ? "contacts" : "particles");
    fuzz::write_file(name, files[k]);
  }
  const std::string dir = fuzz::scratch_dir().string();
  try {
    const auto source = fnet::sources::csv_run_kind().open({{"csv-dir", dir}});
    while (const auto frame = source->next()) fnet::validate(frame->frame);
  } catch (const fnet::CsvError& e) {
    fuzz::require_names(e, {dir});
  } catch (const fnet::FrameError& e) {
    fuzz::require_names(e, {"frame "});
  }
  return 0;
}
