// JSON text from outside the process, read with bounds checked while it is parsed: nesting deeper
// than the bound stops the parser at the opening bracket that passes it (a deep document is never
// built, so nothing recursive — copy, dump, destruction — can overflow the stack), and every
// failure of the parser (syntax, a number outside a double's range, invalid UTF-8) becomes one
// error type whose message names the byte and the cause in words, never nlohmann's exception text.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fnet {

class JsonTextError : public std::runtime_error {
 public:
  enum class Kind { syntax, number_range, too_deep };
  JsonTextError(Kind kind, std::size_t byte, const std::string& message)
      : std::runtime_error(message), kind_(kind), byte_(byte) {}
  Kind kind() const { return kind_; }
  std::size_t byte() const { return byte_; }  // 1-based position of the fault in the text

 private:
  Kind kind_;
  std::size_t byte_;
};

// The nesting a document of fnet's may have: every document it reads is a few levels deep.
inline constexpr std::size_t kMaxJsonDepth = 64;

// Parses `text`; arrays and objects may nest `max_depth` deep (a scalar at top level is depth 0,
// `[1]` depth 1). Throws JsonTextError.
nlohmann::json parse_bounded_json(std::string_view text, std::size_t max_depth = kMaxJsonDepth);

}  // namespace fnet
