#include "server/dem/time_step.hpp"

#include <cmath>
#include <cstddef>

#include "server/dem/contact_forces.hpp"
#include "server/dem/integrator.hpp"
#include "server/dem/walls.hpp"

namespace fnet::sim {
namespace {

constexpr std::size_t kTeamPairsPerGrain = 2;

}  // namespace

void step(Simulation& s, Workers* team) {
  // The team is skipped on a sparse list (fewer than 2 listed pairs per grain, a relaxing
  // lattice), where its synchronization costs more than the split saves; `fnet_sim_bench
  // --threads` measures both sides. Either way the bits are the same.
  Workers* workers = s.list.partner.size() >= kTeamPairsPerGrain * s.n ? team : nullptr;
  const double half_skin = 0.5 * s.list.skin;
  const double limit2 = half_skin * half_skin;
  const bool moved =
      s.params.integrator == Integrator::gear ? gear_predict(s, limit2, workers) : verlet_first_half(s, limit2);
  if (s.walls_moving) ++s.compress_step;
  place_walls(s);
  if (moved || std::abs(wall_offset(s) - s.list.wall_offset_build) > half_skin)
    rebuild(s.list, s.x[0], s.y[0], s.radius, s.inv_mass, s.n, wall_offset(s));
  if (s.params.integrator == Integrator::gear) {
    compute_forces(s, workers, [&s](std::size_t begin, std::size_t end) { gear_correct_range(s, begin, end); });
  } else {
    compute_forces(s, workers);
    verlet_second_half(s);
  }
  ++s.step;
}

void damp_velocities(Simulation& s, double factor) {
  for (std::size_t i = 0; i < s.n; ++i) {
    s.x[1][i] *= factor;
    s.y[1][i] *= factor;
  }
}

}  // namespace fnet::sim
