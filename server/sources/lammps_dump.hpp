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
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "server/sources/text_lines.hpp"

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

// What read_dump throws when the file ends inside a snapshot, which a file still being written
// does until the snapshot is whole.
struct DumpCutShort : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One dump file while LAMMPS writes it. A snapshot is whole once the file holds all of its lines,
// each ended by its newline: its header, and as many rows as its NUMBER OF ATOMS or ENTRIES says.
// LAMMPS writes a snapshot's header before its rows, and a row only whole with its newline, so a
// snapshot that passes is one LAMMPS has finished writing. Plain text only: a gzip stream cannot
// be read before it is closed.
class DumpTail {
 public:
  DumpTail(std::filesystem::path path, DumpKind kind);
  // The snapshots made whole since the last call, in the file's order. A snapshot at fault throws
  // as read_dump does, and so does a file shorter than what was read of it.
  std::vector<DumpSnapshot> read_new();
  // Once the writer is done: throws "FILE:LINE: what" when the file holds more than whole
  // snapshots (the rest of a snapshot cut short).
  void require_read() const;
  // Whether the file held more than whole snapshots at the last read_new: one being written.
  bool pending() const { return pending_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  DumpKind kind_;
  TextLines::Start end_;  // after the last whole snapshot
  bool pending_ = false;
};

// The files a pattern names: a path, or a path whose file name holds the wildcards * ? [...] (as
// LAMMPS's dump.*.txt, or a shell glob), matched in its folder and sorted by name. Throws
// std::runtime_error "PATTERN: ..." when no file matches.
std::vector<std::filesystem::path> dump_files(const std::string& pattern);
// The files the pattern names now, none when none does (a run that has not written them yet).
std::vector<std::filesystem::path> dump_files_now(const std::string& pattern);

}  // namespace fnet::sources
