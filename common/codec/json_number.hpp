// JSON numbers without a DOM: writing a double as nlohmann::json::dump() spells it, and reading a
// number token as nlohmann::json::parse() followed by get<double>() gives it, both bit for bit.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace fnet {

// Enough for every double written by write_json_number.
inline constexpr std::size_t kJsonNumberMaxChars = 32;

// Writes v at out (which has room for kJsonNumberMaxChars) and returns the end. The digits are
// the shortest that read back to v (std::to_chars); the layout is nlohmann's: fixed notation with
// a ".0" for integral values while the decimal point falls within 15 digits, else "1.5e-07";
// -0.0 keeps its sign; NaN and infinities, which JSON cannot hold, become null as in dump().
char* write_json_number(char* out, double v);

// The number token at the start of text (JSON grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?)
// and its length. Integer tokens convert as nlohmann's integers do ("-0" is 0.0). Empty when the
// text does not start with a number token, or its value does not fit a finite double.
struct JsonNumber {
  double value;
  std::size_t length;
};
std::optional<JsonNumber> read_json_number(std::string_view text);

}  // namespace fnet
