#include "common/codec/json_number.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace fnet {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The exponent as nlohmann writes it: a sign and at least two digits.
char* write_exponent(char* out, int e) {
  *out++ = e < 0 ? '-' : '+';
  if (e < 0) e = -e;
  if (e >= 100) *out++ = static_cast<char>('0' + e / 100);
  *out++ = static_cast<char>('0' + e / 10 % 10);
  *out++ = static_cast<char>('0' + e % 10);
  return out;
}

}  // namespace

char* write_json_number(char* out, double v) {
  if (!std::isfinite(v)) {
    std::memcpy(out, "null", 4);
    return out + 4;
  }
  if (std::signbit(v)) {
    *out++ = '-';
    v = -v;
  }
  if (v == 0) {
    std::memcpy(out, "0.0", 3);
    return out + 3;
  }
  // The shortest digits in scientific form, "d[.ddd]e[+-]x", rearranged in place the way
  // nlohmann's format_buffer lays out Grisu's digits.
  char sci[kJsonNumberMaxChars];
  const char* sci_end = std::to_chars(sci, sci + sizeof sci, v, std::chars_format::scientific).ptr;
  char digits[20];
  int k = 0;
  const char* p = sci;
  for (; *p != 'e'; ++p)
    if (*p != '.') digits[k++] = *p;
  int exponent = 0;
  std::from_chars(p + (p[1] == '+' ? 2 : 1), sci_end, exponent);
  const int n = exponent + 1;  // where the decimal point goes, counted from the first digit
  constexpr int kMinExp = -4, kMaxExp = 15;
  if (k <= n && n <= kMaxExp) {  // digits[000].0
    std::memcpy(out, digits, k);
    std::memset(out + k, '0', n - k);
    std::memcpy(out + n, ".0", 2);
    return out + n + 2;
  }
  if (0 < n && n <= kMaxExp) {  // dig.its
    std::memcpy(out, digits, n);
    out[n] = '.';
    std::memcpy(out + n + 1, digits + n, k - n);
    return out + k + 1;
  }
  if (kMinExp < n && n <= 0) {  // 0.[000]digits
    std::memcpy(out, "0.", 2);
    std::memset(out + 2, '0', -n);
    std::memcpy(out + 2 - n, digits, k);
    return out + 2 - n + k;
  }
  *out++ = digits[0];  // d[.igits]e+xx
  if (k > 1) {
    *out++ = '.';
    std::memcpy(out, digits + 1, k - 1);
    out += k - 1;
  }
  *out++ = 'e';
  return write_exponent(out, n - 1);
}

std::optional<JsonNumber> read_json_number(std::string_view text) {
  const char* const first = text.data();
  const char* const end = first + text.size();
  const char* p = first;
  if (p != end && *p == '-') ++p;
  if (p == end || !is_digit(*p)) return std::nullopt;
  if (*p == '0')
    ++p;
  else
    while (p != end && is_digit(*p)) ++p;
  bool integer = true;
  if (p != end && *p == '.') {
    integer = false;
    if (++p == end || !is_digit(*p)) return std::nullopt;
    while (p != end && is_digit(*p)) ++p;
  }
  if (p != end && (*p == 'e' || *p == 'E')) {
    integer = false;
    if (++p != end && (*p == '+' || *p == '-')) ++p;
    if (p == end || !is_digit(*p)) return std::nullopt;
    while (p != end && is_digit(*p)) ++p;
  }
  const auto length = static_cast<std::size_t>(p - first);
  // nlohmann reads an integer token as a 64-bit integer when it fits (then get<double>() rounds it
  // to nearest), and as a double only when it does not.
  if (integer) {
    if (*first == '-') {
      std::int64_t i = 0;
      if (std::from_chars(first, p, i).ec == std::errc()) return JsonNumber{static_cast<double>(i), length};
    } else {
      std::uint64_t u = 0;
      if (std::from_chars(first, p, u).ec == std::errc()) return JsonNumber{static_cast<double>(u), length};
    }
  }
  double value = 0;
  const auto [ptr, ec] = std::from_chars(first, p, value);
  if (ec != std::errc() || ptr != p || !std::isfinite(value)) return std::nullopt;
  return JsonNumber{value, length};
}

}  // namespace fnet
