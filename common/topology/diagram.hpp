// Persistence diagrams as fnet reports them.
#pragma once

#include <cstddef>
#include <vector>

namespace fnet {

// death == kNeverDies marks a class that survives to the end of the filtration (the paper's -1).
inline constexpr double kNeverDies = -1.0;

struct PersistencePoint {
  double birth = 0, death = 0;  // superlevel filtration: birth > death, or death == kNeverDies
  bool operator==(const PersistencePoint&) const = default;
};

using Diagram = std::vector<PersistencePoint>;

// Canonical order for output and comparison: birth descending, then death descending.
void sort_canonical(Diagram& diagram);

}  // namespace fnet
