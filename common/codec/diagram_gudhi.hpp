// fnet's diagrams in the sublevel form that GUDHI, Hera and persim read. fnet's filtration is
// superlevel (a point (b, d) has b >= d, and d = -1 when the class never dies); those tools want
// birth <= death. Negating both coordinates, (b, d) -> (-b, -d), turns one form into the other and
// keeps every L-infinity distance between points and to the diagonal, so every bottleneck and
// Wasserstein distance (internal_p = inf) is the same in both forms.
#pragma once

#include <string>

#include "common/topology/diagram.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {

// How a class that never dies is written: as dying at +inf, GUDHI's own form (GUDHI and Hera then
// match such points only among themselves, by birth, as fnet's `separate` convention does), or
// dying at 0 where the filtration ends (fnet's `floor` convention; a rattler's (0, -1) becomes a
// point on the diagonal and is left out).
enum class GudhiEssential { inf, floor };

// "inf" or "floor"; throws std::invalid_argument for anything else.
GudhiEssential parse_gudhi_essential(const std::string& name);

// One diagram in sublevel form: (-b, -d) per point, the never-dying as `essential` says, in fnet's
// canonical order (so births ascending). Negated zeros are written as +0.
Diagram gudhi_diagram(const Diagram& diagram, GudhiEssential essential);

// Both diagrams as a GUDHI persistence file: a comment line, then one line "DIM BIRTH DEATH" per
// point, PD0 first, numbers in the shortest form that reads back to the same double, +inf as
// "inf". gudhi.read_persistence_intervals_in_dimension(persistence_file=F, only_this_dim=DIM)
// reads one diagram from it as an (n, 2) array; numpy.loadtxt reads it as an (n, 3) one.
std::string diagram_gudhi_text(const FrameDiagrams& diagrams, GudhiEssential essential);

}  // namespace fnet
