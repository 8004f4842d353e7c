#include "common/codec/diagram_json.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/codec/json_number.hpp"

namespace fnet {
namespace {

// The checks diagram_from_json makes; a point failing them goes the slow way for its message.
bool valid_point(double birth, double death) { return death == kNeverDies || birth >= death; }

// Point by point through a small buffer: the text only touches the memory it fills, not all it reserved.
void append_diagram(std::string& text, const Diagram& diagram) {
  text += '[';
  for (std::size_t k = 0; k < diagram.size(); ++k) {
    char point[2 * kJsonNumberMaxChars + 4];
    char* out = point;
    if (k > 0) *out++ = ',';
    *out++ = '[';
    out = write_json_number(out, diagram[k].birth);
    *out++ = ',';
    out = write_json_number(out, diagram[k].death);
    *out++ = ']';
    text.append(point, out);
  }
  text += ']';
}

void append_count(std::string& text, std::size_t n) {
  char buf[24];
  text.append(buf, std::to_chars(buf, buf + sizeof buf, n).ptr);
}

void append_key(std::string& text, std::string_view key) {
  text += '"';
  text += key;
  text += "\":";
}

// One pass over a document of plain shape, looking for one key's diagram. Empty when the text is
// not of that shape or not valid, the key is missing or repeated, or a point is not valid: the
// caller then asks nlohmann::json, which reads what this does not and words every error.
class PlainDocument {
 public:
  explicit PlainDocument(std::string_view text) : p_(text.data()), end_(text.data() + text.size()) {}

  std::optional<Diagram> diagram(std::string_view key) {
    std::optional<Diagram> found;
    if (!take('{')) return std::nullopt;
    if (!take('}')) {
      do {
        std::string_view name;
        if (!string(&name) || !take(':')) return std::nullopt;
        if (name == key) {
          if (found) return std::nullopt;  // nlohmann keeps the last; let it
          found.emplace();
          if (!points(*found)) return std::nullopt;
        } else if (!skip_value(0)) {
          return std::nullopt;
        }
      } while (take(','));
      if (!take('}')) return std::nullopt;
    }
    skip_space();
    if (p_ != end_) return std::nullopt;
    return found;
  }

 private:
  static constexpr int kMaxDepth = 64;

  void skip_space() {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\n' || *p_ == '\r' || *p_ == '\t')) ++p_;
  }
  bool take(char c) {
    skip_space();
    if (p_ == end_ || *p_ != c) return false;
    ++p_;
    return true;
  }
  bool peek(char c) {
    skip_space();
    return p_ != end_ && *p_ == c;
  }
  // Printable ASCII only: escapes and UTF-8 (which nlohmann validates) go the slow way.
  bool string(std::string_view* text) {
    if (!take('"')) return false;
    const char* first = p_;
    while (p_ != end_ && *p_ != '"') {
      const auto c = static_cast<unsigned char>(*p_);
      if (c < 0x20 || c >= 0x80 || c == '\\') return false;
      ++p_;
    }
    if (p_ == end_) return false;
    if (text) *text = {first, static_cast<std::size_t>(p_ - first)};
    ++p_;
    return true;
  }
  bool number(double* value) {
    skip_space();
    const auto n = read_json_number({p_, static_cast<std::size_t>(end_ - p_)});
    if (!n) return false;
    if (value) *value = n->value;
    p_ += n->length;
    return true;
  }
  bool literal(std::string_view word) {
    if (static_cast<std::size_t>(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word) return false;
    p_ += word.size();
    return true;
  }
  bool skip_value(int depth) {
    skip_space();
    if (p_ == end_ || depth > kMaxDepth) return false;
    switch (*p_) {
      case '"':
        return string(nullptr);
      case 't':
        return literal("true");
      case 'f':
        return literal("false");
      case 'n':
        return literal("null");
      case '[':
        ++p_;
        if (take(']')) return true;
        do
          if (!skip_value(depth + 1)) return false;
        while (take(','));
        return take(']');
      case '{':
        ++p_;
        if (take('}')) return true;
        do
          if (!string(nullptr) || !take(':') || !skip_value(depth + 1)) return false;
        while (take(','));
        return take('}');
      default:
        return number(nullptr);
    }
  }
  bool points(Diagram& out) {
    if (!take('[')) return false;
    if (take(']')) return true;
    do {
      double birth = 0, death = 0;
      if (!take('[') || !number(&birth) || !take(',') || !number(&death) || !take(']')) return false;
      if (!valid_point(birth, death)) return false;
      out.push_back({birth, death});
    } while (take(','));
    return take(']');
  }

  const char* p_;
  const char* end_;
};

}  // namespace

nlohmann::json to_json(const Diagram& diagram) {
  nlohmann::json out = nlohmann::json::array();
  for (const PersistencePoint& p : diagram) out.push_back({p.birth, p.death});
  return out;
}

nlohmann::json to_json(const FrameDiagrams& d) {
  return {{diagram_key(0), to_json(d.pd0)},
          {diagram_key(1), to_json(d.pd1)},
          {"vertices", d.vertices},
          {"edges", d.edges},
          {"triangles", d.triangles}};
}

std::string diagram_document_text(const FrameDiagrams& d) {
  std::string text;
  text.reserve(128 + (2 * kJsonNumberMaxChars + 4) * (d.pd0.size() + d.pd1.size()));
  // Keys in nlohmann's order (sorted), as to_json(d).dump() prints them.
  append_key(text += '{', "edges");
  append_count(text, d.edges);
  append_key(text += ',', diagram_key(0));
  append_diagram(text, d.pd0);
  append_key(text += ',', diagram_key(1));
  append_diagram(text, d.pd1);
  append_key(text += ',', "triangles");
  append_count(text, d.triangles);
  append_key(text += ',', "vertices");
  append_count(text, d.vertices);
  text += '}';
  return text;
}

Diagram diagram_from_json(const nlohmann::json& value) {
  if (!value.is_array()) throw std::invalid_argument("a diagram must be an array of [birth, death] pairs");
  Diagram out;
  out.reserve(value.size());
  for (std::size_t k = 0; k < value.size(); ++k) {
    const auto& p = value[k];
    const std::string where = "point " + std::to_string(k);
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw std::invalid_argument(where + ": expected [birth, death], got " + p.dump());
    const double birth = p[0].get<double>(), death = p[1].get<double>();
    if (!std::isfinite(birth) || !std::isfinite(death)) throw std::invalid_argument(where + ": non-finite value");
    if (death != kNeverDies && birth < death)
      throw std::invalid_argument(where + ": birth " + p[0].dump() + " < death " + p[1].dump() +
                                  " (superlevel diagrams have birth >= death)");
    out.push_back({birth, death});
  }
  return out;
}

std::string diagram_key(int dim) { return "pd" + std::to_string(dim); }

Diagram document_diagram(const nlohmann::json& document, int dim) {
  const std::string key = diagram_key(dim);
  if (!document.is_object() || !document.contains(key))
    throw std::invalid_argument("no \"" + key +
                                "\" diagram (expected a diagram document {\"pd0\": [...], \"pd1\": [...]})");
  try {
    return diagram_from_json(document[key]);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(key + ": " + e.what());
  }
}

}  // namespace fnet

namespace fnet {

Diagram parse_document_diagram(std::string_view text, int dim, const std::string& source) {
  if (std::optional<Diagram> plain = PlainDocument(text).diagram(diagram_key(dim))) return std::move(*plain);
  return document_diagram(parse_bounded_json(text, kDiagramDocumentLimits, source), dim);
}

}  // namespace fnet
