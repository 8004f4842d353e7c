#include "common/codec/frame_csv.hpp"

#include <array>
#include <charconv>
#include <fstream>
#include <string>
#include <string_view>

namespace fnet {
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string_view field =
        line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\t' || field.back() == '\r'))
      field.remove_suffix(1);
    out.push_back(field);
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// Reads a CSV whose header must contain `names`; calls row(values) with the fields in that order.
template <std::size_t K, class Row>
void read_table(const std::filesystem::path& path, const std::array<std::string_view, K>& names, Row row) {
  std::ifstream in(path);
  if (!in) throw CsvError(path.string() + ": cannot open file");
  std::string line;
  std::size_t line_no = 0;
  const auto fail = [&](const std::string& what) {
    throw CsvError(path.string() + ":" + std::to_string(line_no) + ": " + what);
  };
  std::array<std::size_t, K> column{};
  std::size_t width = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (split(line) == std::vector<std::string_view>{""}) continue;  // blank line
    const auto header = split(line);
    width = header.size();
    for (std::size_t k = 0; k < K; ++k) {
      std::size_t c = 0;
      while (c < header.size() && header[c] != names[k]) ++c;
      if (c == header.size()) {
        std::string expected;
        for (auto n : names) {
          if (!expected.empty()) expected += ',';
          expected.append(n);
        }
        fail("header lacks column '" + std::string(names[k]) + "' (expected " + expected + ")");
      }
      column[k] = c;
    }
    break;
  }
  if (width == 0) fail("empty file: no header");
  std::array<std::string_view, K> fields;
  while (std::getline(in, line)) {
    ++line_no;
    const auto cells = split(line);
    if (cells.size() == 1 && cells[0].empty()) continue;
    if (cells.size() != width)
      fail("expected " + std::to_string(width) + " fields, found " + std::to_string(cells.size()));
    for (std::size_t k = 0; k < K; ++k) fields[k] = cells[column[k]];
    row(fields, fail, line_no);
  }
}

template <class T, class Fail>
T parse(std::string_view text, std::string_view column, Fail fail) {
  T value{};
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && text.front() == '+') {
    ++first;
    if (first != last && (*first == '-' || *first == '+')) first = last;  // "+-2" is not a number
  }
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (text.empty() || ec != std::errc() || ptr != last)
    fail("column '" + std::string(column) + "': '" + std::string(text) + "' is not a valid " +
         (std::is_integral_v<T> ? "integer" : "number"));
  return value;
}

}  // namespace

std::vector<Contact> read_contacts_csv(const std::filesystem::path& path) {
  std::vector<Contact> out;
  static constexpr std::array<std::string_view, 4> names{"i", "j", "fn", "ft"};
  read_table(path, names, [&](const auto& f, const auto& fail, std::size_t) {
    out.push_back({parse<std::int64_t>(f[0], "i", fail), parse<std::int64_t>(f[1], "j", fail),
                   parse<double>(f[2], "fn", fail), parse<double>(f[3], "ft", fail)});
  });
  return out;
}

std::vector<Particle> read_particles_csv(const std::filesystem::path& path) {
  struct Row {
    std::int64_t id;
    Particle particle;
    std::size_t line;
  };
  std::vector<Row> rows;
  static constexpr std::array<std::string_view, 4> names{"id", "x", "y", "r"};
  read_table(path, names, [&](const auto& f, const auto& fail, std::size_t line) {
    rows.push_back(
        {parse<std::int64_t>(f[0], "id", fail),
         Particle{parse<double>(f[1], "x", fail), parse<double>(f[2], "y", fail), parse<double>(f[3], "r", fail)},
         line});
  });
  std::vector<Particle> out(rows.size());
  std::vector<std::size_t> seen_at(rows.size(), 0);  // line of the row that gave each id
  for (const Row& r : rows) {
    const std::string where = path.string() + ":" + std::to_string(r.line) + ": ";
    if (r.id < 0 || static_cast<std::size_t>(r.id) >= rows.size())
      throw CsvError(where + "particle id " + std::to_string(r.id) + " out of range [0, " +
                     std::to_string(rows.size()) + "): ids must be 0..n-1");
    if (seen_at[r.id])
      throw CsvError(where + "particle id " + std::to_string(r.id) + " appears twice (first on line " +
                     std::to_string(seen_at[r.id]) + ")");
    seen_at[r.id] = r.line;
    out[r.id] = r.particle;
  }
  return out;
}

Frame read_frame_csv(const std::filesystem::path& contacts, const std::optional<std::filesystem::path>& particles) {
  Frame frame;
  frame.label = contacts.string();
  frame.contacts = read_contacts_csv(contacts);
  if (particles) {
    frame.particles = read_particles_csv(*particles);
    frame.particle_count = frame.particles.size();
  } else {
    frame.particle_count = implied_particle_count(frame.contacts);
  }
  return frame;
}

}  // namespace fnet
