// LAMMPS text dumps as LAMMPS writes them: a per-atom dump (dump custom, ITEM: ATOMS) or a local
// dump (dump local, ITEM: ENTRIES), one snapshot per ITEM: TIMESTEP, any number of snapshots per
// file, plain or gzip-compressed. Values are kept as the dump holds them; what the columns mean
// is for the reader of the snapshot (lammps_frame.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fnet::sources {

enum class DumpKind { atoms, entries };

// An orthogonal box: a triclinic one (BOX BOUNDS xy xz yz) is refused when read.
struct DumpBox {
  std::array<double, 3> lo{}, hi{};
  std::array<bool, 3> periodic{};  // boundary flag "pp" on that axis
};

struct DumpSnapshot {
  std::string file;
  std::size_t line = 0;  // of its ITEM: TIMESTEP
  std::uint64_t timestep = 0;
  std::optional<double> time;  // ITEM: TIME, where dump_modify time yes writes it
  DumpBox box;
  std::vector<std::string> columns;
  std::size_t first_row_line = 0;
  // Row-major, rows() × columns.size(); a value that is not a number is NaN, which the reader of
  // a column it uses rejects (columns it ignores may hold words).
  std::vector<double> values;

  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  double at(std::size_t row, std::size_t column) const { return values[row * columns.size() + column]; }
  std::optional<std::size_t> column(std::string_view name) const;
  // "FILE:LINE" of a row, and of the snapshot's ITEM: TIMESTEP.
  std::string where(std::size_t row) const;
  std::string where() const;
};

// Every snapshot of one file, in the file's order. Throws std::runtime_error "FILE:LINE: what" for
// a file that is not such a dump of `kind`: a missing or unknown ITEM, a count or bound that is not
// a number, a triclinic box, a row with too few or too many values, a snapshot cut short.
std::vector<DumpSnapshot> read_dump(const std::filesystem::path& path, DumpKind kind);

// The files a pattern names: a path, or a path whose file name holds the wildcards * ? [...] (as
// LAMMPS's dump.*.txt, or a shell glob), matched in its folder and sorted by name. Throws
// std::runtime_error "PATTERN: ..." when no file matches.
std::vector<std::filesystem::path> dump_files(const std::string& pattern);

}  // namespace fnet::sources
