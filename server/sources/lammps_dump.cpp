#include "server/sources/lammps_dump.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "server/sources/text_lines.hpp"

namespace fnet::sources {

namespace {

constexpr std::uint64_t kReservedRows = 4096;  // rows of a snapshot reserved before they are read

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t k = 0;
  while (true) {
    k = line.find_first_not_of(" \t", k);
    if (k == std::string_view::npos) return out;
    const std::size_t end = std::min(line.find_first_of(" \t", k), line.size());
    out.push_back(line.substr(k, end - k));
    k = end;
  }
}

// A number as LAMMPS prints it; NaN for anything else (a word, or a number with trailing text).
double number(std::string_view word) {
  double value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size()) return std::numeric_limits<double>::quiet_NaN();
  return value;
}

class DumpReader {
 public:
  DumpReader(const std::filesystem::path& path, DumpKind kind, const TextLines::Start& start = {})
      : lines_(path, start), kind_(kind) {}

  std::vector<DumpSnapshot> read() {
    std::vector<DumpSnapshot> out;
    while (next_item()) out.push_back(timestep_snapshot());
    return out;
  }

  // The whole snapshots from the start on; `end` is moved past the last of them.
  std::vector<DumpSnapshot> read_whole(TextLines::Start& end) {
    std::vector<DumpSnapshot> out;
    try {
      while (next_item()) {
        out.push_back(timestep_snapshot());
        end.offset = lines_.offset();
        end.line = lines_.number();
      }
    } catch (const DumpCutShort&) {
      // The rest is still being written.
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(lines_.path().string() + ":" + std::to_string(lines_.number()) + ": " + what);
  }
  [[noreturn]] void cut_short(const std::string& what) const {
    throw DumpCutShort(lines_.path().string() + ":" + std::to_string(lines_.number()) + ": " + what +
                       " (file cut short)");
  }

  DumpSnapshot timestep_snapshot() {
    if (item_ != "TIMESTEP") fail("expected ITEM: TIMESTEP, found ITEM: " + item_);
    return snapshot();
  }

  // Reads the next "ITEM: NAME rest" line into item_ and item_rest_; false at the end of the file.
  bool next_item() {
    if (!lines_.next(line_)) return false;
    if (line_.rfind("ITEM: ", 0) != 0) fail("expected an ITEM: line, found \"" + line_.substr(0, 60) + "\"");
    const std::string_view body = std::string_view(line_).substr(6);
    std::size_t name_end = body.size();
    for (const char* name :
         {"TIMESTEP", "TIME", "UNITS", "NUMBER OF ATOMS", "NUMBER OF ENTRIES", "BOX BOUNDS", "ATOMS", "ENTRIES"})
      if (body.rfind(name, 0) == 0 && (body.size() == std::strlen(name) || body[std::strlen(name)] == ' ')) {
        name_end = std::strlen(name);
        break;
      }
    item_ = std::string(body.substr(0, name_end));
    item_rest_ = std::string(body.substr(name_end));
    return true;
  }

  void require_item(const std::string& name, const std::string& within) {
    if (!next_item()) cut_short(within + " ends before ITEM: " + name);
    if (item_ != name) fail("expected ITEM: " + name + ", found ITEM: " + item_);
  }

  void require_line(const std::string& what) {
    if (!lines_.next(line_)) cut_short("the file ends before " + what);
  }

  std::uint64_t count_line(const std::string& what) {
    require_line(what);
    const auto w = words(line_);
    std::uint64_t value = 0;
    if (w.size() != 1 ||
        std::from_chars(w[0].data(), w[0].data() + w[0].size(), value).ptr != w[0].data() + w[0].size())
      fail(what + " is not a whole number: \"" + line_.substr(0, 60) + "\"");
    return value;
  }

  DumpSnapshot snapshot() {
    DumpSnapshot s;
    s.file = lines_.path().string();
    s.line = lines_.number();
    s.timestep = count_line("the TIMESTEP");
    const std::string within = "the snapshot of TIMESTEP " + std::to_string(s.timestep);
    const std::string count_item = kind_ == DumpKind::atoms ? "NUMBER OF ATOMS" : "NUMBER OF ENTRIES";
    while (true) {
      if (!next_item()) cut_short(within + " ends before ITEM: " + count_item);
      if (item_ == "TIME") {
        require_line("the TIME");
        s.time = number(words(line_).empty() ? std::string_view() : words(line_)[0]);
        if (!std::isfinite(*s.time)) fail("the TIME is not a number");
      } else if (item_ == "UNITS") {
        require_line("the UNITS");
      } else if (item_ == count_item) {
        break;
      } else {
        std::string message = "expected ITEM: " + count_item + ", found ITEM: " + item_;
        if (item_ == "NUMBER OF ATOMS" || item_ == "NUMBER OF ENTRIES") message += wrong_kind();
        fail(message);
      }
    }
    const std::uint64_t rows = count_line("the " + count_item);
    require_item("BOX BOUNDS", within);
    box(s.box);
    require_item(kind_ == DumpKind::atoms ? "ATOMS" : "ENTRIES", within);
    for (const std::string_view w : words(item_rest_)) s.columns.emplace_back(w);
    if (s.columns.empty()) fail("ITEM: " + item_ + " names no column");
    s.first_row_line = lines_.number() + 1;
    // The count is the file's word, not what it holds: reserve no more than a few thousand rows
    // before they are read (a count past memory is then "cut short", not an allocation failure
    // or a large allocation per snapshot of a file of a few lines); larger snapshots grow.
    s.values.reserve(std::min<std::uint64_t>(rows, kReservedRows) * s.columns.size());
    for (std::uint64_t r = 0; r < rows; ++r) {
      if (!lines_.next(line_))
        cut_short(within + " ends after " + std::to_string(r) + " of its " + std::to_string(rows) + " rows");
      const auto w = words(line_);
      if (w.size() != s.columns.size()) {
        std::string message =
            "a row of " + std::to_string(w.size()) + " values under " + std::to_string(s.columns.size()) + " columns";
        if (r + 1 == rows) message += " (file cut short?)";
        fail(message);
      }
      for (const std::string_view v : w) s.values.push_back(number(v));
    }
    return s;
  }

  std::string wrong_kind() const {
    return kind_ == DumpKind::atoms ? " (a local dump where a per-atom dump was expected)"
                                    : " (a per-atom dump where a local dump was expected)";
  }

  void box(DumpBox& box) {
    const auto flags = words(item_rest_);
    if (std::any_of(flags.begin(), flags.end(), [](std::string_view f) { return f == "xy" || f == "xz" || f == "yz"; }))
      fail("a triclinic box (BOX BOUNDS xy xz yz), which fnet does not read; dump an orthogonal box");
    for (std::size_t axis = 0; axis < 3; ++axis) {
      box.periodic[axis] = axis < flags.size() && flags[axis] == "pp";
      require_line("the box bounds");
      const auto w = words(line_);
      if (w.size() != 2 || !std::isfinite(number(w[0])) || !std::isfinite(number(w[1])))
        fail("a box bound line that is not two numbers: \"" + line_.substr(0, 60) + "\"");
      box.lo[axis] = number(w[0]);
      box.hi[axis] = number(w[1]);
    }
  }

  TextLines lines_;
  DumpKind kind_;
  std::string line_, item_, item_rest_;
};

bool has_wildcard(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

}  // namespace

std::optional<std::size_t> DumpSnapshot::column(std::string_view name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) return std::nullopt;
  return static_cast<std::size_t>(it - columns.begin());
}

std::string DumpSnapshot::where(std::size_t row) const { return file + ":" + std::to_string(first_row_line + row); }
std::string DumpSnapshot::where() const { return file + ":" + std::to_string(line); }

std::vector<DumpSnapshot> read_dump(const std::filesystem::path& path, DumpKind kind) {
  return DumpReader(path, kind).read();
}

DumpTail::DumpTail(std::filesystem::path path, DumpKind kind) : path_(std::move(path)), kind_(kind) {
  end_.whole_lines_only = true;
}

std::vector<DumpSnapshot> DumpTail::read_new() {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path_, error);
  pending_ = false;
  if (error || size == end_.offset) return {};
  if (size < end_.offset)
    throw std::runtime_error(path_.string() + ": shrank from " + std::to_string(end_.offset) + " to " +
                             std::to_string(size) + " bytes while it was read (a dump rewritten?)");
  std::vector<DumpSnapshot> out = DumpReader(path_, kind_, end_).read_whole(end_);
  pending_ = end_.offset < size;
  return out;
}

void DumpTail::require_read() const {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path_, error);
  if (error || size == end_.offset) return;
  // Reading the rest as it stands names what is missing.
  DumpReader(path_, kind_, end_).read();
  throw std::runtime_error(path_.string() + ":" + std::to_string(end_.line + 1) + ": a snapshot cut short");
}

std::vector<std::filesystem::path> dump_files(const std::string& pattern) {
  std::vector<std::filesystem::path> out = dump_files_now(pattern);
  if (out.empty()) throw std::runtime_error(pattern + (has_wildcard(pattern) ? ": no file matches" : ": no such file"));
  return out;
}

std::vector<std::filesystem::path> dump_files_now(const std::string& pattern) {
  namespace fs = std::filesystem;
  const fs::path path(pattern);
  if (!has_wildcard(pattern)) {
    if (!fs::is_regular_file(path)) return {};
    return {path};
  }
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (has_wildcard(folder.string()))
    throw std::runtime_error(pattern + ": wildcards are read in the file name only, not in its folder");
  const std::string name = path.filename().string();
  std::vector<fs::path> out;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
    if (entry.is_regular_file() && fnmatch(name.c_str(), entry.path().filename().c_str(), 0) == 0)
      out.push_back(entry.path());
  if (error) throw std::runtime_error(pattern + ": cannot list " + folder.string() + " (" + error.message() + ")");
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace fnet::sources
