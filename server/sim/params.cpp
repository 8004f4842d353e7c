#include "server/sim/params.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace fnet::sim {

Constants derive(const Params& p) {
  Constants c;
  const double ln_e = std::log(p.en);
  const double m_bar = 0.5;  // two grains of the mean mass
  c.tau_c = std::sqrt((std::numbers::pi * std::numbers::pi + ln_e * ln_e) * m_bar / p.kn);
  c.gamma_n = -2 * ln_e / c.tau_c;
  c.kn = p.kn;
  c.kt = p.kt_ratio * p.kn;
  c.dt = c.tau_c / p.dt_divisor;
  c.wall_speed = p.compression_speed / c.tau_c;
  c.mean_d2 = 1 + p.polydispersity * p.polydispersity / 12;
  return c;
}

void validate(const Params& p) {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("invalid parameter: ") + what);
  };
  require(p.particles >= 1, "particles must be >= 1");
  require(p.polydispersity >= 0 && p.polydispersity < 2, "polydispersity must be in [0, 2)");
  require(p.mu >= 0 && std::isfinite(p.mu), "mu must be >= 0");
  require(p.kn > 0 && std::isfinite(p.kn), "kn must be > 0");
  require(p.en > 0 && p.en <= 1, "en must be in (0, 1]");
  require(p.kt_ratio >= 0 && std::isfinite(p.kt_ratio), "kt_ratio must be >= 0");
  require(p.compression_speed > 0 && std::isfinite(p.compression_speed), "compression_speed must be > 0");
  require(p.dt_divisor >= 1 && std::isfinite(p.dt_divisor), "dt_divisor must be >= 1");
  require(p.rho_final > 0 && p.rho_final < 1, "rho_final must be in (0, 1)");
  require(p.frames >= 2, "frames must be >= 2");
  require(p.box > 2 && std::isfinite(p.box), "box must be > 2");
  require(p.wall_diameter > 0 && p.wall_diameter <= p.box, "wall_diameter must be in (0, box]");
  require(p.initial_speed >= 0 && std::isfinite(p.initial_speed), "initial_speed must be >= 0");
  require(p.relax_energy >= 0, "relax_energy must be >= 0");
  require(p.relax_max_time >= 0, "relax_max_time must be >= 0");
  require(p.skin > 0 && p.skin < 2, "skin must be in (0, 2)");
  // The square lattice: one site per grain, spacing box / ceil(sqrt(N)) must be at least the mean diameter.
  const double side = std::ceil(std::sqrt(static_cast<double>(p.particles)));
  require(p.box / side >= 1.0, "box too small for the particles on a square lattice (spacing < d_ave)");
}

const char* to_string(Integrator integrator) { return integrator == Integrator::gear ? "gear" : "verlet"; }

Integrator parse_integrator(const std::string& name) {
  if (name == "gear") return Integrator::gear;
  if (name == "verlet") return Integrator::verlet;
  throw std::invalid_argument("invalid parameter: integrator must be gear or verlet, not '" + name + "'");
}

void apply_json(Params& p, const nlohmann::json& config) {
  if (!config.is_object()) throw std::invalid_argument("config: expected a JSON object");
  for (const auto& [key, value] : config.items()) {
    const auto number = [&]() {
      if (!value.is_number()) throw std::invalid_argument("config: '" + key + "' must be a number");
      return value.get<double>();
    };
    const auto count = [&]() {
      if (!value.is_number_integer() || value.get<std::int64_t>() < 0)
        throw std::invalid_argument("config: '" + key + "' must be a non-negative integer");
      return value.get<std::uint64_t>();
    };
    if (key == "particles")
      p.particles = count();
    else if (key == "polydispersity")
      p.polydispersity = number();
    else if (key == "mu")
      p.mu = number();
    else if (key == "kn")
      p.kn = number();
    else if (key == "en")
      p.en = number();
    else if (key == "kt_ratio")
      p.kt_ratio = number();
    else if (key == "compression_speed")
      p.compression_speed = number();
    else if (key == "dt_divisor")
      p.dt_divisor = number();
    else if (key == "rho_final")
      p.rho_final = number();
    else if (key == "frames")
      p.frames = count();
    else if (key == "seed")
      p.seed = count();
    else if (key == "box")
      p.box = number();
    else if (key == "wall_diameter")
      p.wall_diameter = number();
    else if (key == "initial_speed")
      p.initial_speed = number();
    else if (key == "relax_energy")
      p.relax_energy = number();
    else if (key == "relax_max_time")
      p.relax_max_time = number();
    else if (key == "skin")
      p.skin = number();
    else if (key == "integrator") {
      if (!value.is_string()) throw std::invalid_argument("config: 'integrator' must be a string");
      p.integrator = parse_integrator(value.get<std::string>());
    } else {
      throw std::invalid_argument("config: unknown key '" + key + "'");
    }
  }
}

nlohmann::json to_json(const Params& p) {
  return {{"particles", p.particles},
          {"polydispersity", p.polydispersity},
          {"mu", p.mu},
          {"kn", p.kn},
          {"en", p.en},
          {"kt_ratio", p.kt_ratio},
          {"compression_speed", p.compression_speed},
          {"dt_divisor", p.dt_divisor},
          {"rho_final", p.rho_final},
          {"frames", p.frames},
          {"seed", p.seed},
          {"box", p.box},
          {"wall_diameter", p.wall_diameter},
          {"initial_speed", p.initial_speed},
          {"relax_energy", p.relax_energy},
          {"relax_max_time", p.relax_max_time},
          {"skin", p.skin},
          {"integrator", to_string(p.integrator)}};
}

}  // namespace fnet::sim
