// Parameters of the paper's system (Kramár et al. 2014, Appendix A) and the constants derived
// from them. Internal units: d_ave = 1, mean grain mass = 1, g = 1 (so k_n = 4000 as in the
// paper); the paper's time unit τ_c is a derived constant. Speeds users type (v_c) and times we
// report are in units of τ_c.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <variant>

#include <nlohmann/json_fwd.hpp>

namespace fnet::sim {

enum class Integrator { gear, verlet };

// The defaults are the paper's; what each field means is in param_fields() (params.cpp).
struct Params {
  std::uint64_t particles = 2000;
  double polydispersity = 0.4;
  double mu = 0.5;
  double kn = 4000;
  double en = 0.5;
  double kt_ratio = 0.8;
  double compression_speed = 2.5e-5;
  double dt_divisor = 50;
  double rho_initial = 0.63;
  double rho_final = 0.90;
  std::uint64_t frames = 100;
  std::uint64_t seed = 1;
  std::optional<double> box;  // unset: sized so that the grains fill rho_initial of it
  double wall_diameter = 1;
  double initial_speed = 0.1;
  double relax_energy = 1e-12;
  double relax_damping = 0.01;
  double relax_max_time = 2e5;
  double skin = 0.15;
  Integrator integrator = Integrator::gear;
};

// One entry per parameter: its JSON key (the flag is the key with '-' for '_'), where it lives,
// what it means, and the rule a valid value obeys. The JSON codec (both ways), the command-line
// flags, their help and validate() all walk this one table.
struct ParamField {
  using Member =
      std::variant<double Params::*, std::uint64_t Params::*, std::optional<double> Params::*, Integrator Params::*>;
  const char* name;
  Member member;
  const char* help;                  // units included; the default is appended from Params{}
  bool (*ok)(double) = nullptr;      // null: any value of the member's type
  const char* rule = "";             // what ok() demands, for messages
  const char* unset_help = nullptr;  // for an optional member: what leaving it unset means
};

std::span<const ParamField> param_fields();
std::string flag_name(const ParamField& field);  // "--kt-ratio"
// A field's value as --help and messages show it ("2.5e-05", "gear").
std::string format_value(const Params& p, const ParamField& field);
// Sets a field from a flag's text; throws std::invalid_argument naming the flag unless the whole
// text is a number of the field's kind (a non-negative integer for counts) obeying its rule.
void set_from_text(Params& p, const ParamField& field, const std::string& text);

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

// Throws std::invalid_argument naming the offending parameter. Rules that need the grains
// (the box against the lattice, rho_final against the start) are checked by make_lattice.
void validate(const Params& p);

const char* to_string(Integrator integrator);
Integrator parse_integrator(const std::string& name);

// Config file: a JSON object whose keys are the Params field names; unknown keys are errors.
void apply_json(Params& p, const nlohmann::json& config);
// The config file `file` (fnet-simd --config) applied to p: at most 1 MiB of JSON, nested at most
// 16 deep, read by apply_json. Throws std::invalid_argument "FILE: what" (the file cannot be read,
// is not JSON, or a key or value is wrong); the rules of the values are validate()'s.
void apply_config_file(Params& p, const std::filesystem::path& file);
nlohmann::json to_json(const Params& p);

}  // namespace fnet::sim
