// Which fnet made a result: its version (CMake's project version, the Python package's too) and
// the git commit it was built from. Every program prints them for --version, and every store, run
// file, CSV export and server.status answer records them beside the results.
#pragma once

#include <string>
#include <string_view>

namespace fnet {

struct BuildInfo {
  std::string_view version;  // "MAJOR.MINOR.PATCH"
  std::string_view commit;   // 40 hex digits, "-dirty" appended for uncommitted changes; or "unknown"
};

BuildInfo build_info();

// "PROGRAM VERSION (commit COMMIT)", the first line of every program's --version.
std::string version_line(std::string_view program);

// The current time as ISO 8601 UTC to the second ("2026-12-03T09:47:32Z"): when a file was written.
std::string utc_timestamp();

}  // namespace fnet
