#include "server/sources/force_balance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fnet::sources {

ForceBalance force_balance(const LammpsFrame& frame, double tolerance) {
  const RunFrame& run = frame.run;
  if (frame.contact_forces.size() != run.frame.contacts.size() || frame.wall_forces.size() != run.wall_contacts.size())
    throw std::invalid_argument("the force balance needs the force vectors, which the pair dump does not give");
  // In a 2D run the vectors' z is 0: the same sums are the balance in the plane.
  std::vector<std::array<double, 3>> net(run.frame.particle_count, {0.0, 0.0, 0.0});
  double total = 0;
  const auto add = [&](std::size_t grain, const std::array<double, 3>& f, double sign) {
    for (std::size_t k = 0; k < 3; ++k) net[grain][k] += sign * f[k];
  };
  for (std::size_t k = 0; k < run.frame.contacts.size(); ++k) {
    const Contact& c = run.frame.contacts[k];
    const auto& f = frame.contact_forces[k];
    add(static_cast<std::size_t>(c.i), f, 1.0);
    add(static_cast<std::size_t>(c.j), f, -1.0);
    total += std::hypot(f[0], f[1], f[2]);
  }
  for (std::size_t k = 0; k < run.wall_contacts.size(); ++k) {
    const auto& f = frame.wall_forces[k];
    add(run.wall_contacts[k].particle, f, 1.0);
    total += std::hypot(f[0], f[1], f[2]);
  }
  ForceBalance out;
  const std::size_t count = run.frame.contacts.size() + run.wall_contacts.size();
  if (count == 0) return out;
  out.mean_force = total / static_cast<double>(count);
  for (std::size_t g = 0; g < net.size(); ++g) {
    const double relative = std::hypot(net[g][0], net[g][1], net[g][2]) / out.mean_force;
    if (relative > tolerance) out.unbalanced.push_back({static_cast<std::uint32_t>(g), relative});
  }
  std::sort(out.unbalanced.begin(), out.unbalanced.end(),
            [](const GrainImbalance& a, const GrainImbalance& b) { return a.net > b.net; });
  return out;
}

}  // namespace fnet::sources
