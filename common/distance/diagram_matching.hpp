// The matching behind a diagram distance: which point of one diagram goes with which point of the
// other, or with the diagonal, and the length of each term.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/distance/essential_convention.hpp"
#include "common/topology/diagram.hpp"

namespace fnet {

// One term: a point of a with a point of b, or one of them with the diagonal (-1 on the other
// side). Indices are positions in the diagrams as the distance was given them.
struct MatchedPair {
  std::int64_t a = -1, b = -1;
  // L-infinity length under the convention the distance used: ||p - q||_inf between the points
  // as the distance sees them (floor: (b, -1) is (b, 0)), |x - y| / 2 to the diagonal; under
  // separate, two never-dying classes are |birth_a - birth_b| apart.
  double length = 0;
  bool operator==(const MatchedPair&) const = default;
};

// Every point of a and of b in exactly one term; points the distance ignores (on the diagonal
// under the convention, such as rattlers under floor) go to the diagonal at length 0. d_Wq =
// (sum of length^q)^(1/q) and d_B = the longest length, to rounding (d_B exactly).
struct DiagramMatching {
  std::vector<MatchedPair> pairs;
  std::size_t longest = 0;  // index of the first longest term (for d_B: one that attains it); 0 if none
};

// Assembles a matching from terms between the views of two diagrams, then adds every point of
// either diagram left out of the views at length 0, and finds the longest term.
class MatchingBuilder {
 public:
  MatchingBuilder(const ConventionView& va, const ViewSources& sa, std::size_t size_a, const ConventionView& vb,
                  const ViewSources& sb, std::size_t size_b);

  void pair(std::uint32_t i, std::uint32_t j);  // view points a_i and b_j
  void a_to_diagonal(std::uint32_t i);
  void b_to_diagonal(std::uint32_t j);
  // Under separate: the essential births matched in sorted order (as the distances match them).
  void essentials();
  // Every view point of both sides to the diagonal.
  void all_to_diagonal();
  DiagramMatching finish();

 private:
  const ConventionView &va_, &vb_;
  const ViewSources &sa_, &sb_;
  std::vector<std::uint8_t> used_a_, used_b_;
  DiagramMatching out_;
};

// The view of a diagram, with its sources when `sources` is not null (a matching was asked for).
ConventionView view_for(const Diagram& diagram, EssentialConvention convention, ViewSources* sources);

// The matching of two diagrams that are equal under the convention: equal points together.
DiagramMatching identity_matching(const Diagram& a, const Diagram& b, EssentialConvention convention);

}  // namespace fnet
