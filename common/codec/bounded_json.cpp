#include "common/codec/bounded_json.hpp"

#include <optional>

namespace fnet {
namespace {

using Dom = nlohmann::detail::json_sax_dom_parser<nlohmann::json>;

// The DOM builder with the depth counted: a container past the limit stops the parse, and so does
// any parse error, whose reason is kept instead of thrown.
class BoundedDom : public Dom {
 public:
  BoundedDom(nlohmann::json& out, std::size_t max_depth) : Dom(out, false), max_depth_(max_depth) {}

  bool start_object(std::size_t n) { return enter() && Dom::start_object(n); }
  bool start_array(std::size_t n) { return enter() && Dom::start_array(n); }
  bool end_object() {
    --depth_;
    return Dom::end_object();
  }
  bool end_array() {
    --depth_;
    return Dom::end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string&, const Exception& e) {
    std::string reason = e.what();
    // nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 3: ..." without
    // its tag; a parse error names line and column, the others (a number outside a double's
    // range) the byte.
    if (const std::size_t tag_end = reason.find("] ");
        reason.rfind("[json.exception.", 0) == 0 && tag_end != reason.npos)
      reason.erase(0, tag_end + 2);
    if (e.id >= 100 && e.id < 200)
      reason.insert(0, "not JSON: ");
    else
      reason += " at byte " + std::to_string(position);
    problem_ = std::move(reason);
    return false;
  }

  const std::optional<std::string>& problem() const { return problem_; }
  bool too_deep() const { return too_deep_; }

 private:
  bool enter() {
    if (++depth_ <= max_depth_) return true;
    problem_ = "nested deeper than " + std::to_string(max_depth_) + " arrays and objects";
    too_deep_ = true;
    return false;
  }

  std::size_t max_depth_;
  std::size_t depth_ = 0;
  std::optional<std::string> problem_;
  bool too_deep_ = false;
};

}  // namespace

nlohmann::json parse_bounded_json(std::string_view text, const JsonLimits& limits, const std::string& source) {
  if (text.size() > limits.max_bytes)
    throw JsonInputError(
        JsonInputError::Kind::too_large, source,
        std::to_string(text.size()) + " bytes of JSON, more than the limit of " + std::to_string(limits.max_bytes));
  nlohmann::json out;
  BoundedDom dom(out, limits.max_depth);
  const bool ok = nlohmann::json::sax_parse(text, &dom, nlohmann::json::input_format_t::json, true);
  if (!ok || dom.problem())
    throw JsonInputError(dom.too_deep() ? JsonInputError::Kind::too_deep : JsonInputError::Kind::not_json, source,
                         dom.problem().value_or("not JSON"));
  return out;
}

}  // namespace fnet
