// The contact-list reader, fnet-analyze's --contacts C.csv [--particles P.csv] (the CSV frame reader
// of common/codec under it), then the checks and the diagrams of the frame it reads.
// Input: the contacts CSV [@@@@ the particles CSV].
#include <cstddef>
#include <cstdint>
#include <optional>

#include "common/analysis/frame_analysis.hpp"
#include "common/codec/frame_csv.hpp"
#include "server/sources/source_kinds.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto files = fuzz::input_files(data, size);
  fuzz::clear_scratch();
  const auto contacts = fuzz::write_file("contacts.csv", files[0]);
  std::optional<std::filesystem::path> particles;
  if (files.size() > 1) particles = fuzz::write_file("particles.csv", files[1]);
  try {
    const auto source = fnet::sources::open_frame_files(contacts, particles);
    const fnet::RunFrame frame = fnet::sources::next_frame(*source);
    fnet::validate(frame.frame);
    fnet::analyze_frame(frame.frame);
  } catch (const fnet::CsvError& e) {
    fuzz::require_names(e, {contacts.string(), particles.value_or(contacts).string()});
  } catch (const fnet::FrameError& e) {
    fuzz::require_names(e, {contacts.string()});
  }
  return 0;
}
