// Time integration of the grains (translation and rotation).
//
// Gear's predictor–corrector for second-order equations with five values (x and its first four
// scaled derivatives): the predictor is the Taylor (Pascal-triangle) step, the corrector scales
// the difference between the acceleration from the forces at the predicted state and the
// predicted one by (19/120, 3/4, 1, 1/2, 1/12) (Allen & Tildesley, Sec. 3.2). The forces see the
// predicted positions and velocities, as velocity-dependent (damped) forces require.
//
// Velocity Verlet, for comparison: half kick, drift, forces at (x(t+Δt), v(t+Δt/2)), half kick
// (LAMMPS's fix nve/sphere does the same).
#pragma once

#include <cstddef>

namespace fnet::sim {

struct Simulation;
class Workers;

// The predictors return whether a grain has moved farther than √limit2 since the last list
// build. gear_predict splits the grains over a team when given one (element-wise: the same bits).
bool gear_predict(Simulation& s, double limit2, Workers* workers = nullptr);
// The corrector of grains [begin, end) (element-wise), run by compute_forces as each thread's
// grains get their forces.
void gear_correct_range(Simulation& s, std::size_t begin, std::size_t end);
bool verlet_first_half(Simulation& s, double limit2);
void verlet_second_half(Simulation& s);

}  // namespace fnet::sim
