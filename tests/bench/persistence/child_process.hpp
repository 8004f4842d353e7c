// Running one measurement in a forked child, so that its peak memory is its own.
#pragma once

#include <cstdio>
#include <functional>
#include <string>

namespace fnet::bench {

struct ChildRun {
  bool ok = false;
  std::string failure;          // "exit 1", "killed by signal 9", ... when !ok
  long peak_rss_kib = 0;        // the child's ru_maxrss from wait4: inherited pages count too
  std::FILE* output = nullptr;  // what the child wrote, rewound; the caller closes it
};

// Forks; the child runs body(output) and exits. The parent waits and collects the child's
// resource usage. Output goes through a temporary file, never a pipe, so the parent can start
// reading only after the child has finished (and holds none of its results while it runs).
ChildRun run_in_child(const std::function<void(std::FILE*)>& body);

}  // namespace fnet::bench
