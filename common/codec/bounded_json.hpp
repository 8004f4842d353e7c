// JSON text from outside the process (files, announcements, stores) read into a DOM within limits:
// its size, and the depth of its nesting, checked while it is parsed (nlohmann's SAX interface),
// so that no document, however nested, costs more stack than max_depth levels, and no parse error
// of any kind (syntax, a number outside a double's range) escapes as anything but JsonInputError.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fnet {

struct JsonLimits {
  std::size_t max_bytes = std::size_t{1} << 20;
  std::size_t max_depth = 64;  // arrays and objects open at once
};

// what() is "<source>: <reason>": "not JSON: parse error at line L, column C: ...", "number overflow
// parsing '1e999' at byte B", or the limit exceeded.
class JsonInputError : public std::runtime_error {
 public:
  enum class Kind { not_json, too_large, too_deep };  // a number outside a double's range is not_json
  JsonInputError(Kind kind, const std::string& source, const std::string& reason)
      : std::runtime_error(source + ": " + reason), kind_(kind), reason_(reason) {}
  Kind kind() const { return kind_; }
  const std::string& reason() const { return reason_; }  // what() without the source

 private:
  Kind kind_;
  std::string reason_;
};

// The document `text` holds; `source` names it in every message (a file, "config_json").
nlohmann::json parse_bounded_json(std::string_view text, const JsonLimits& limits, const std::string& source);

}  // namespace fnet
