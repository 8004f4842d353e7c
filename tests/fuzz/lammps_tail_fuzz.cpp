// A LAMMPS dump followed while LAMMPS writes it (fnet-analyze publish --follow): DumpTail reading
// the file after each piece is appended, then told the writer is done. Input: "atoms" or "entries"
// (the kind of dump) [@@@@ the dump's first piece [@@@@ the next piece ...]].
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "server/sources/lammps_dump.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto files = fuzz::input_files(data, size);
  fuzz::clear_scratch();
  const auto kind = files[0].starts_with("entries") ? fnet::sources::DumpKind::entries : fnet::sources::DumpKind::atoms;
  const auto path = fuzz::write_file("dump.txt", "");
  try {
    fnet::sources::DumpTail tail(path, kind);
    for (std::size_t k = 1; k < files.size(); ++k) {
      std::ofstream(path, std::ios::binary | std::ios::app)
          .write(files[k].data(), static_cast<std::streamsize>(files[k].size()));
      for (const fnet::sources::DumpSnapshot& s : tail.read_new())
        if (s.values.size() != s.rows() * s.columns.size()) throw std::logic_error("a snapshot of ragged rows");
    }
    tail.require_read();
  } catch (const fnet::sources::DumpCutShort& e) {
    fuzz::require_names(e, {path.string()});
  } catch (const std::runtime_error& e) {
    fuzz::require_names(e, {path.string()});
  }
  return 0;
}
