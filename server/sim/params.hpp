// Parameters of the paper's system (Kramár et al. 2014, Appendix A) and the constants derived
// from them. Internal units: d_ave = 1, mean grain mass = 1, g = 1 (so k_n = 4000 as in the
// paper); the paper's time unit τ_c is a derived constant. Speeds users type (v_c) and times we
// report are in units of τ_c.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace fnet::sim {

enum class Integrator { gear, verlet };

struct Params {
  std::size_t particles = 2000;
  double polydispersity = 0.4;        // r_p: diameters uniform in [1 - r_p/2, 1 + r_p/2]
  double mu = 0.5;                    // Coulomb coefficient μ_s (grain–grain and grain–wall)
  double kn = 4000;                   // normal spring, units m g / d
  double en = 0.5;                    // normal restitution of two mean grains; fixes γ_n = γ_t
  double kt_ratio = 0.8;              // k_t / k_n
  double compression_speed = 2.5e-5;  // v_c, d / τ_c, each wall
  double dt_divisor = 50;             // Δt = τ_c / dt_divisor
  double rho_final = 0.90;
  std::size_t frames = 100;  // frames over the compression, first at its start, last at rho_final
  std::uint64_t seed = 1;
  double box = 50;              // initial side of the free interior, d
  double wall_diameter = 1;     // monodisperse wall particles
  double initial_speed = 0.1;   // initial grain velocities uniform in a disk of this radius, d / τ_c
  double relax_energy = 1e-7;   // relaxation ends when kinetic energy per grain < this, m d² / τ_c²
  double relax_max_time = 2e5;  // give up relaxing after this long (τ_c) and compress anyway
  double skin = 0.15;           // Verlet-list skin, d
  Integrator integrator = Integrator::gear;
};

// Constants the engine uses, in internal units (time unit √(d/g)).
struct Constants {
  double tau_c = 0;    // binary collision time of two mean grains (m̄ = 1/2)
  double gamma_n = 0;  // γ_n = γ_t, multiplies m̄ v
  double kn = 0, kt = 0;
  double dt = 0;
  double wall_speed = 0;  // d per internal time unit
  double mean_d2 = 1;     // <d²> of the diameter distribution; mass = d² / <d²>
};

Constants derive(const Params& p);

// Throws std::invalid_argument naming the offending parameter.
void validate(const Params& p);

const char* to_string(Integrator integrator);
Integrator parse_integrator(const std::string& name);

// Config file: a JSON object whose keys are the Params field names; unknown keys are errors.
void apply_json(Params& p, const nlohmann::json& config);
nlohmann::json to_json(const Params& p);

}  // namespace fnet::sim
