// How a distance treats classes that never die (death == kNeverDies), as README and proto/api.md
// document them:
//   floor     (default) the class dies where the superlevel filtration ends, at 0: (b, -1) -> (b, 0).
//             Rattlers (0, -1) land on the diagonal; distances stay scale-invariant.
//   sentinel  -1 is taken literally as a coordinate (Perseus, the paper's text). Not scale-invariant:
//             any change in the count of never-dying classes costs >= 0.5.
//   separate  never-dying classes are matched only among themselves, by birth (GUDHI, Hera);
//             the distance is +inf when their counts differ.
// floor is the default because, measured on the LAMMPS frames in tests/data near jamming, the
// literal reading pins d_B(PD1) at 0.50-0.55 while floor gives 0.15-0.29, the paper's range.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/topology/diagram.hpp"

namespace fnet {

enum class EssentialConvention { floor, sentinel, separate };

std::string_view to_string(EssentialConvention convention);
// Parses "floor" / "sentinel" / "separate"; throws std::invalid_argument naming the bad value.
EssentialConvention parse_essential_convention(std::string_view text);

// A diagram point as a point of the plane: x = birth, y = death.
struct PlanePoint {
  double x = 0, y = 0;
  bool operator==(const PlanePoint&) const = default;
};

// A diagram as the distances see it under one convention.
struct ConventionView {
  std::vector<PlanePoint> points;        // matched with the diagonal allowed; none lies on the diagonal
  std::vector<double> essential_births;  // only under separate; ascending
};

// Throws std::invalid_argument on a non-finite coordinate. Points on the diagonal are dropped: they
// are free to match to the diagonal and never help a matching, so every distance ignores them.
ConventionView apply_convention(const Diagram& diagram, EssentialConvention convention);

// Where each entry of a view came from: its index in the diagram.
struct ViewSources {
  std::vector<std::uint32_t> points;     // parallel to ConventionView::points
  std::vector<std::uint32_t> essential;  // parallel to ConventionView::essential_births
};

// The same view, and into `sources` the index in `diagram` of each of its entries (essential
// births of equal value keep the diagram's order).
ConventionView apply_convention(const Diagram& diagram, EssentialConvention convention, ViewSources& sources);

// Under separate: the essential births matched in sorted order, which is optimal for every
// q >= 1 and for the bottleneck. Empty message when the counts agree.
std::string essential_count_mismatch(const ConventionView& a, const ConventionView& b);

}  // namespace fnet
