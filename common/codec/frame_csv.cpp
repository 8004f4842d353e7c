#include "common/codec/frame_csv.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <numeric>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>

#include "common/codec/file_text.hpp"
#include "common/topology/contact_force.hpp"

namespace fnet {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t'; }

// A field without the blanks around it (and the '\r' of a CRLF line end).
std::string_view trimmed(const char* first, const char* last) {
  while (first != last && is_space(*first)) ++first;
  while (last != first && (is_space(last[-1]) || last[-1] == '\r')) --last;
  return {first, static_cast<std::size_t>(last - first)};
}

bool is_blank(std::string_view line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return is_space(c) || c == '\r'; });
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  const char* first = line.data();
  const char* const end = line.data() + line.size();
  while (true) {
    const char* comma = std::find(first, end, ',');
    out.push_back(trimmed(first, comma));
    if (comma == end) return out;
    first = comma + 1;
  }
}

// The lines of a text as std::getline gives them: split at '\n', a last line without one counts,
// and a final '\n' starts no empty line.
class Lines {
 public:
  explicit Lines(std::string_view text) : next_(text.data()), end_(text.data() + text.size()) {}

  bool next(std::string_view& line) {
    if (next_ == end_) return false;
    const auto* newline = static_cast<const char*>(std::memchr(next_, '\n', static_cast<std::size_t>(end_ - next_)));
    const char* stop = newline ? newline : end_;
    line = {next_, static_cast<std::size_t>(stop - next_)};
    next_ = newline ? newline + 1 : end_;
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }
  std::string_view rest() const { return {next_, static_cast<std::size_t>(end_ - next_)}; }
  // Counts the line that ends at `stop` (its '\n', or the end of the text) as read.
  void take_through(const char* stop) {
    next_ = stop == end_ ? end_ : stop + 1;
    ++number_;
  }

 private:
  const char* next_;
  const char* end_;
  std::size_t number_ = 0;
};

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

// The number at p, which p then passes; false if there is none.
template <class V>
bool take_number(const char*& p, const char* end, V& value) {
  const auto [ptr, ec] = std::from_chars(p, end, value);
  if (ec != std::errc() || ptr == p) return false;
  p = ptr;
  return true;
}

// take_number into the k-th of the values.
template <class Tuple, std::size_t... I>
bool take_value(std::size_t k, const char*& p, const char* end, Tuple& values, std::index_sequence<I...>) {
  bool ok = false;
  ((k == I && (ok = take_number(p, end, std::get<I>(values)))), ...);
  return ok;
}

// A row as fnet writes it, at the start of text: every value a bare number, the fields split by
// commas alone, parsed where they stand (from_chars finds each one's end, the last one's is the
// line's). Returns where the line ends (its '\n' or the end of the text), or null at anything else
// (blanks, a '+', a wrong count, a bad value): the caller then reads the line field by field,
// which says what is wrong. Where this succeeds, that reading would give the same values.
template <class... T>
const char* read_plain_row(std::string_view text, const std::vector<std::size_t>& slot, std::tuple<T...>& values) {
  const char* p = text.data();
  const char* const end = text.data() + text.size();
  const std::size_t width = slot.size();
  for (std::size_t c = 0; c < width; ++c) {
    if (slot[c] == sizeof...(T)) {
      while (p != end && *p != ',' && *p != '\n') ++p;
    } else if (!take_value(slot[c], p, end, values, std::index_sequence_for<T...>{})) {
      return nullptr;
    }
    if (c + 1 < width) {
      if (p == end || *p != ',') return nullptr;
      ++p;
    }
  }
  if (p != end && *p == '\r') ++p;
  return p == end || *p == '\n' ? p : nullptr;
}

template <std::size_t K>
using ColumnNames = std::array<std::string_view, K>;

// What read_table found in a header: which form, and which of its columns (the optional ones may
// be missing).
template <std::size_t K>
struct TableShape {
  std::size_t form = 0;
  std::array<bool, K> present{};
};

// Reads a CSV whose header must contain the first `required` columns of one of `forms` (the first
// form it has them all of; the error names the first form's missing column), and may contain the
// others; calls reserve(n, form) with an upper bound on the number of rows and the form found, then
// row(values, line) with the values of those columns, of types T..., in that order (a column the
// header lacks is 0). One pass over the file held whole; a row costs no allocation.
template <class... T, class Reserve, class Row>
TableShape<sizeof...(T)> read_table(const std::filesystem::path& path,
                                    const std::vector<ColumnNames<sizeof...(T)>>& forms, std::size_t required,
                                    Reserve reserve, Row row) {
  constexpr std::size_t K = sizeof...(T);
  TableShape<K> shape;
  std::size_t& form = shape.form;
  const std::optional<FileText> file = FileText::read(path);
  if (!file) throw CsvError(path.string() + ": cannot open file");
  const std::string_view text = file->view();
  Lines lines(text);
  const auto fail = [&](const std::string& what) {
    throw CsvError(path.string() + ":" + std::to_string(lines.number()) + ": " + what);
  };
  constexpr std::size_t kUnused = K;
  std::vector<std::size_t> slot;  // per column of the file: which of `names` it holds, or kUnused
  std::string_view line;
  while (lines.next(line)) {
    if (is_blank(line)) continue;
    const auto header = split(line);
    const auto has = [&](std::string_view name) {
      return std::find(header.begin(), header.end(), name) != header.end();
    };
    form = static_cast<std::size_t>(std::find_if(forms.begin(), forms.end(),
                                                 [&](const ColumnNames<K>& names) {
                                                   return std::all_of(names.begin(), names.begin() + required, has);
                                                 }) -
                                    forms.begin());
    if (form == forms.size()) {
      std::string expected;
      for (const ColumnNames<K>& names : forms) {
        if (!expected.empty()) expected += " or ";
        for (std::size_t k = 0; k < required; ++k) {
          if (k) expected += ',';
          expected.append(names[k]);
        }
      }
      const ColumnNames<K>& first = forms.front();
      const std::string_view missing =
          *std::find_if(first.begin(), first.begin() + required, [&](auto n) { return !has(n); });
      fail("header lacks column '" + std::string(missing) + "' (expected " + expected + ")");
    }
    slot.assign(header.size(), kUnused);
    for (std::size_t k = 0; k < K; ++k) {
      const auto c = static_cast<std::size_t>(std::find(header.begin(), header.end(), forms[form][k]) - header.begin());
      shape.present[k] = c < header.size();
      if (shape.present[k] && slot[c] == kUnused) slot[c] = k;
    }
    break;
  }
  if (slot.empty()) fail("empty file: no header");
  const std::size_t width = slot.size();
  // Vectors sized once, from the length of the first row: growing them would copy at every
  // doubling, and counting the lines first would cost a pass over the file.
  const std::string_view rest = lines.rest();
  reserve(rest.size() / (std::min(rest.find('\n'), rest.size()) + 1) + 1, form);
  std::tuple<T...> values;
  std::array<std::string_view, K> fields;
  while (true) {
    if (const char* stop = read_plain_row(lines.rest(), slot, values)) {
      lines.take_through(stop);
    } else {
      if (!lines.next(line)) break;
      const char* first = line.data();
      const char* const end = line.data() + line.size();
      std::size_t c = 0;
      while (true) {
        const char* comma = std::find(first, end, ',');
        if (c < width && slot[c] != kUnused) fields[slot[c]] = trimmed(first, comma);
        ++c;
        if (comma == end) break;
        first = comma + 1;
      }
      if (c != width) {
        if (c == 1 && is_blank(line)) continue;
        fail("expected " + std::to_string(width) + " fields, found " + std::to_string(c));
      }
      [&]<std::size_t... I>(std::index_sequence<I...>) {
        ((shape.present[I] &&
          (std::get<I>(values) = parse<std::tuple_element_t<I, std::tuple<T...>>>(fields[I], forms[form][I], fail),
           true)),
         ...);
      }
      (std::index_sequence_for<T...>{});
    }
    row(values, lines.number());
  }
  return shape;
}

}  // namespace

ContactsCsv read_contacts_table(const std::filesystem::path& path) {
  ContactsCsv out;
  bool vectors = false;  // then each row's line is kept, for the messages of contacts_from_vectors
  // fz, the third component of a vector, is optional (a 2D frame's forces lie in its plane); the
  // magnitudes form ignores it.
  static const std::vector<ColumnNames<5>> forms{{"i", "j", "fn", "ft", "fz"}, {"i", "j", "fx", "fy", "fz"}};
  const TableShape<5> shape = read_table<std::int64_t, std::int64_t, double, double, double>(
      path, forms, 4,
      [&](std::size_t n, std::size_t chosen) {
        out.rows.reserve(n);
        vectors = chosen == 1;
        if (vectors) out.lines.reserve(n);
      },
      [&](const auto& v, std::size_t line) {
        out.rows.push_back({std::get<0>(v), std::get<1>(v), std::get<2>(v), std::get<3>(v)});
        if (vectors) {
          out.lines.push_back(line);
          out.fz.push_back(std::get<4>(v));
        }
      });
  out.forces = shape.form == 0 ? ContactForces::magnitudes : ContactForces::vectors;
  if (!shape.present[4]) out.fz.clear();
  return out;
}

std::vector<Contact> read_contacts_csv(const std::filesystem::path& path) {
  ContactsCsv table = read_contacts_table(path);
  if (table.forces == ContactForces::vectors)
    throw CsvError(path.string() + ": contact forces given as vectors (fx,fy[,fz]) need the particles' positions");
  return std::move(table.rows);
}

namespace {

std::vector<Contact> contacts_from_vectors(const std::filesystem::path& path, const ContactsCsv& table,
                                           const std::vector<Particle>& particles) {
  std::vector<Contact> out;
  out.reserve(table.rows.size());
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const Contact& row = table.rows[k];
    for (const std::int64_t g : {row.i, row.j})
      if (g < 0 || static_cast<std::size_t>(g) >= particles.size())
        throw CsvError(path.string() + ":" + std::to_string(table.lines[k]) + ": particle index " + std::to_string(g) +
                       " is not in the particles CSV (" + std::to_string(particles.size()) + " particles)");
    const Particle& a = particles[static_cast<std::size_t>(row.i)];
    const Particle& b = particles[static_cast<std::size_t>(row.j)];
    const ContactForceParts parts =
        split_contact_force({a.x - b.x, a.y - b.y, a.z - b.z}, {row.fn, row.ft, table.fz.empty() ? 0.0 : table.fz[k]});
    out.push_back({row.i, row.j, parts.fn, parts.ft});
  }
  return out;
}

}  // namespace

ParticlesCsv read_particles_table(const std::filesystem::path& path) {
  // Rows land in the table in file order; their ids are kept only once one is out of order (the
  // table then moves each row to its id). In order, as fnet writes them, ids 0..n-1 need no check.
  std::vector<Particle> table;
  std::vector<std::int64_t> ids;
  std::vector<std::size_t> lines;
  bool in_order = true;
  // z, optional: a table with a z column is a 3D frame's.
  static const std::vector<ColumnNames<5>> forms{{"id", "x", "y", "r", "z"}};
  const TableShape<5> shape = read_table<std::int64_t, double, double, double, double>(
      path, forms, 4,
      [&](std::size_t n, std::size_t) {
        table.reserve(n);
        lines.reserve(n);
      },
      [&](const auto& v, std::size_t line) {
        const std::int64_t id = std::get<0>(v);
        if (in_order && id != static_cast<std::int64_t>(table.size())) {
          in_order = false;
          ids.resize(table.size());
          std::iota(ids.begin(), ids.end(), std::int64_t{0});
        }
        if (!in_order) ids.push_back(id);
        table.push_back({std::get<1>(v), std::get<2>(v), std::get<3>(v), std::get<4>(v)});
        lines.push_back(line);
      });
  const int dimension = shape.present[4] ? 3 : 2;
  if (in_order) return {dimension, std::move(table)};
  std::vector<Particle> out(table.size());
  std::vector<std::size_t> seen_at(table.size(), 0);  // line of the row that gave each id
  for (std::size_t k = 0; k < table.size(); ++k) {
    const std::int64_t id = ids[k];
    if (id < 0 || static_cast<std::size_t>(id) >= table.size() || seen_at[id]) {
      const std::string where = path.string() + ":" + std::to_string(lines[k]) + ": ";
      if (id < 0 || static_cast<std::size_t>(id) >= table.size())
        throw CsvError(where + "particle id " + std::to_string(id) + " out of range [0, " +
                       std::to_string(table.size()) + "): ids must be 0..n-1");
      throw CsvError(where + "particle id " + std::to_string(id) + " appears twice (first on line " +
                     std::to_string(seen_at[id]) + ")");
    }
    seen_at[id] = lines[k];
    out[id] = table[k];
  }
  return {dimension, std::move(out)};
}

std::vector<Particle> read_particles_csv(const std::filesystem::path& path) {
  return read_particles_table(path).particles;
}

Frame read_frame_csv(const std::filesystem::path& contacts, const std::optional<std::filesystem::path>& particles) {
  Frame frame;
  frame.label = contacts.string();
  ContactsCsv table = read_contacts_table(contacts);
  if (particles) {
    ParticlesCsv read = read_particles_table(*particles);
    frame.dimension = read.dimension;
    frame.particles = std::move(read.particles);
    frame.particle_count = frame.particles.size();
  } else if (table.forces == ContactForces::vectors) {
    throw CsvError(contacts.string() +
                   ": contact forces given as vectors (fx,fy[,fz]) need the particles CSV, whose positions give the "
                   "line of centres");
  }
  frame.contacts = table.forces == ContactForces::vectors ? contacts_from_vectors(contacts, table, frame.particles)
                                                          : std::move(table.rows);
  if (!particles) frame.particle_count = implied_particle_count(frame.contacts);
  return frame;
}

}  // namespace fnet
