// The contact law of the paper (Appendix A), evaluated over the Verlet list:
//   normal      F_n = k_n x − γ_n m̄ v_n                                  (A1), not clipped at 0
//   spring      ξ += v_t Δt, then ξ ← ξ − n (n·ξ)                         (A2, A3)
//   test force  F_t* = −k_t ξ − γ_t m̄ v_t                                 (A4)
//   Coulomb     |F_t| = min(μ|F_n|, |F_t*|), and when capped ξ is redefined so that
//               −k_t ξ − γ_t m̄ v_t equals the capped force                (A5)
// v_t is the relative velocity of the contact point, rotation included (v_i − v_j minus its
// normal part, minus (r_i ω_i + r_j ω_j) ẑ×n). Torques act at the surfaces (−r_i n and +r_j n).
// m̄ = 1/(1/m_i + 1/m_j); wall particles have 1/m = 0. This is what LAMMPS's gran/hooke/history
// computes with the same constants.
#pragma once

#include <cstddef>
#include <functional>

namespace fnet::sim {

struct Simulation;
class Workers;

// Zeroes and accumulates fx, fy, torque of every body (wall particles receive their reactions),
// advances ξ, and records fn, ft, touching per pair. With a team of more than one thread, the
// pairs are evaluated in parallel (each force stored with its pair), then every body sums its
// pairs in the order the serial loop adds them: the same bits for any team size. `then` is called
// for slices of grains whose forces are complete (with a team, on the thread that summed them,
// so that an element-wise update such as the corrector needs no loop of its own).
using GrainsDone = std::function<void(std::size_t begin, std::size_t end)>;
void compute_forces(Simulation& s, Workers* workers = nullptr, const GrainsDone& then = {});

}  // namespace fnet::sim
