#include "tests/support/diagram_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tests/reference/flag_filtration.hpp"
#include "tests/reference/reference_persistence.hpp"

namespace fnet {

void PrintTo(const PersistencePoint& point, std::ostream* out) {
  const auto precision = out->precision(17);
  *out << "(" << point.birth << ", " << point.death << ")";
  out->precision(precision);
}

}  // namespace fnet

namespace fnet::testing {

std::string describe(const Frame& frame) {
  std::ostringstream s;
  s.precision(17);
  s << "particle_count=" << frame.particle_count << "\ni,j,fn,ft\n";
  constexpr std::size_t kShown = 300;  // a LAMMPS frame in full would bury the failure
  for (std::size_t k = 0; k < std::min(frame.contacts.size(), kShown); ++k) {
    const Contact& c = frame.contacts[k];
    s << c.i << "," << c.j << "," << c.fn << "," << c.ft << "\n";
  }
  if (frame.contacts.size() > kShown) s << "... " << frame.contacts.size() - kShown << " more contacts\n";
  return s.str();
}

std::string describe(const Diagram& diagram) {
  std::ostringstream s;
  s << "{";
  for (const PersistencePoint& p : diagram) {
    s << " ";
    PrintTo(p, &s);
  }
  s << " }";
  return s.str();
}

FrameDiagrams fast_path(const Frame& frame, ForceKind kind) { return compute_persistence(build_network(frame, kind)); }

::testing::AssertionResult matches_reference(const Frame& frame, ForceKind kind) {
  const ForceNetwork network = build_network(frame, kind);
  const FrameDiagrams fast = compute_persistence(network);
  std::ostringstream why;
  why.precision(17);
  // The mean is checked on its own, to a few ulps: its last bit depends on the order of summation,
  // which the fast path may choose. The diagrams are then compared bit for bit with the reference
  // normalized by the same mean, so they test the persistence, not the rounding of a sum.
  const double own_mean = reference::mean_force(frame, kind);
  if (!(std::fabs(network.mean_force - own_mean) <= 1e-15 * own_mean))
    why << "mean force differs: fast " << network.mean_force << ", reference " << own_mean << "\n";
  const reference::Diagrams ref = reference::persistence(frame, kind, network.mean_force);
  if (fast.pd0 != ref.pd0)
    why << "PD0 differs\n  fast:      " << describe(fast.pd0) << "\n  reference: " << describe(ref.pd0) << "\n";
  if (fast.pd1 != ref.pd1)
    why << "PD1 differs\n  fast:      " << describe(fast.pd1) << "\n  reference: " << describe(ref.pd1) << "\n";
  if (fast.vertices != ref.vertices || fast.edges != ref.edges || fast.triangles != ref.triangles)
    why << "counts differ: fast " << fast.vertices << "/" << fast.edges << "/" << fast.triangles << ", reference "
        << ref.vertices << "/" << ref.edges << "/" << ref.triangles << " (vertices/edges/triangles)\n";
  if (why.str().empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << to_string(kind) << " forces:\n" << why.str() << describe(frame);
}

::testing::AssertionResult nearly_equal(const Diagram& a, const Diagram& b, double tolerance) {
  const auto close = [tolerance](double x, double y) {
    if (x == kNeverDies || y == kNeverDies) return x == y;
    return std::fabs(x - y) <= tolerance * std::max(std::fabs(x), std::fabs(y));
  };
  bool same = a.size() == b.size();
  for (std::size_t k = 0; same && k < a.size(); ++k)
    same = close(a[k].birth, b[k].birth) && close(a[k].death, b[k].death);
  if (same) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << describe(a) << "\n  vs " << describe(b) << "\n  (relative tolerance "
                                       << tolerance << ")";
}

}  // namespace fnet::testing
