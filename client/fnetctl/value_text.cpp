#include "client/fnetctl/value_text.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace fnet::client {

std::string exact_number(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (std::isnan(value)) return "nan";
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return ec == std::errc() ? std::string(buf, end) : std::string();
}

std::string rounded_number(double value, int significant) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.precision(significant);
  s << value;
  return s.str();
}

std::string distance_cell(const nlohmann::json& value, bool infinite, CellStyle style) {
  if (infinite) return "inf";
  if (value.is_null()) return style == CellStyle::table ? "-" : "";
  const double v = value.get<double>();
  return style == CellStyle::table ? rounded_number(v, 8) : exact_number(v);
}

}  // namespace fnet::client
