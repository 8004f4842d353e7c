#include <ctime>

#include "common/build_info/build_info.hpp"

namespace fnet {

std::string version_line(std::string_view program) {
  const BuildInfo b = build_info();
  return std::string(program) + " " + std::string(b.version) + " (commit " + std::string(b.commit) + ")";
}

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return std::string(text, n);
}

}  // namespace fnet
