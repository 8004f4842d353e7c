#include "server/dem/params.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/codec/bounded_json.hpp"
#include "common/codec/file_text.hpp"

namespace fnet::sim {
namespace {

template <class... F>
struct Overload : F... {
  using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;  // clang before 17 deduces no aggregate's arguments

constexpr bool positive(double v) { return v > 0 && std::isfinite(v); }
constexpr bool non_negative(double v) { return v >= 0 && std::isfinite(v); }

const std::array kFields{
    ParamField{"particles", &Params::particles, "number of grains N", [](double v) { return v >= 1; }, "must be >= 1"},
    ParamField{"polydispersity", &Params::polydispersity, "r_p: diameters uniform in [1-r_p/2, 1+r_p/2]",
               [](double v) { return v >= 0 && v < 2; }, "must be in [0, 2)"},
    ParamField{"mu", &Params::mu, "Coulomb friction coefficient mu_s (grain-grain and grain-wall)", non_negative,
               "must be >= 0"},
    ParamField{"kn", &Params::kn, "normal spring constant k_n, m g/d", positive, "must be > 0"},
    ParamField{"en", &Params::en, "normal restitution of two mean grains (fixes gamma_n = gamma_t)",
               [](double v) { return v > 0 && v <= 1; }, "must be in (0, 1]"},
    ParamField{"kt_ratio", &Params::kt_ratio, "k_t / k_n", non_negative, "must be >= 0"},
    ParamField{"compression_speed", &Params::compression_speed, "wall speed v_c, each wall, d/tau_c", positive,
               "must be > 0"},
    ParamField{"dt_divisor", &Params::dt_divisor, "time step = tau_c / this",
               [](double v) { return v >= 1 && std::isfinite(v); }, "must be >= 1"},
    ParamField{"rho_initial", &Params::rho_initial, "packing fraction of the start: sizes the box (unless --box)",
               [](double v) { return v > 0 && v < 1; }, "must be in (0, 1)"},
    ParamField{"rho_final", &Params::rho_final, "packing fraction that ends the compression (above the start)",
               [](double v) { return v > 0 && v < 1; }, "must be in (0, 1)"},
    ParamField{"frames", &Params::frames, "frames over the compression, first (the relaxed start) and last included",
               [](double v) { return v >= 2; }, "must be >= 2"},
    ParamField{"seed", &Params::seed, "random seed: diameters and initial velocities"},
    ParamField{"box", &Params::box, "initial side of the free interior, d; overrides --rho-initial",
               [](double v) { return v > 2 && std::isfinite(v); }, "must be > 2", "sized by rho_initial"},
    ParamField{"wall_diameter", &Params::wall_diameter, "diameter of the monodisperse wall particles, d", positive,
               "must be > 0"},
    ParamField{"initial_speed", &Params::initial_speed,
               "initial grain velocities uniform in a disk of this radius, d/tau_c", non_negative, "must be >= 0"},
    ParamField{"relax_energy", &Params::relax_energy,
               "relaxation ends when the translational kinetic energy per grain is below this, m d^2/tau_c^2",
               non_negative, "must be >= 0"},
    ParamField{"relax_damping", &Params::relax_damping,
               "during the relaxation only, grain velocities decay at this rate, 1/tau_c (0: no damping)",
               [](double v) { return v >= 0 && v < 1e3; }, "must be in [0, 1000)"},
    ParamField{"relax_max_time", &Params::relax_max_time, "longest relaxation, tau_c (then it compresses anyway)",
               non_negative, "must be >= 0"},
    ParamField{"skin", &Params::skin, "Verlet-list skin, d", [](double v) { return v > 0 && v < 2; },
               "must be in (0, 2)"},
    ParamField{"integrator", &Params::integrator, "gear (the paper's Gear predictor-corrector) or verlet"},
};

std::string shortest(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

[[noreturn]] void invalid(const ParamField& f, const std::string& what) {
  throw std::invalid_argument("invalid parameter " + std::string(f.name) + " (" + flag_name(f) + "): " + what);
}

void check_rule(const ParamField& f, double v) {
  if (f.ok && !f.ok(v)) invalid(f, std::string(f.rule) + ", not " + shortest(v));
}

}  // namespace

std::span<const ParamField> param_fields() { return kFields; }

std::string flag_name(const ParamField& field) {
  std::string flag = std::string("--") + field.name;
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

std::string format_value(const Params& p, const ParamField& field) {
  return std::visit(Overload{[&](double Params::*m) { return shortest(p.*m); },
                             [&](std::uint64_t Params::*m) { return std::to_string(p.*m); },
                             [&](std::optional<double> Params::*m) {
                               return (p.*m) ? shortest(*(p.*m)) : std::string(field.unset_help);
                             },
                             [&](Integrator Params::*m) { return std::string(to_string(p.*m)); }},
                    field.member);
}

void set_from_text(Params& p, const ParamField& field, const std::string& text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  const auto real = [&] {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(begin, end, v);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
      throw std::invalid_argument(flag_name(field) + " expects a number, not '" + text + "'");
    check_rule(field, v);
    return v;
  };
  std::visit(
      Overload{[&](double Params::*m) { p.*m = real(); }, [&](std::optional<double> Params::*m) { p.*m = real(); },
               [&](std::uint64_t Params::*m) {
                 std::uint64_t v = 0;
                 const auto [ptr, ec] = std::from_chars(begin, end, v);
                 if (text.empty() || ec != std::errc() || ptr != end)
                   throw std::invalid_argument(flag_name(field) + " expects a non-negative integer, not '" + text +
                                               "'");
                 check_rule(field, static_cast<double>(v));
                 p.*m = v;
               },
               [&](Integrator Params::*m) { p.*m = parse_integrator(text); }},
      field.member);
}

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
  for (const ParamField& f : kFields) {
    std::visit(Overload{[&](double Params::*m) { check_rule(f, p.*m); },
                        [&](std::uint64_t Params::*m) { check_rule(f, static_cast<double>(p.*m)); },
                        [&](std::optional<double> Params::*m) {
                          if (p.*m) check_rule(f, *(p.*m));
                        },
                        [](Integrator Params::*) {}},
               f.member);
  }
  if (!p.box && p.rho_final <= p.rho_initial)
    throw std::invalid_argument("invalid parameter rho_final (--rho-final): " + shortest(p.rho_final) +
                                " is not above the start's packing fraction, rho_initial " + shortest(p.rho_initial));
  if (p.box && p.wall_diameter > *p.box)
    throw std::invalid_argument("invalid parameter: wall_diameter must be at most the box side");
}

const char* to_string(Integrator integrator) { return integrator == Integrator::gear ? "gear" : "verlet"; }

Integrator parse_integrator(const std::string& name) {
  if (name == "gear") return Integrator::gear;
  if (name == "verlet") return Integrator::verlet;
  throw std::invalid_argument("invalid parameter integrator (--integrator): gear or verlet, not '" + name + "'");
}

void apply_json(Params& p, const nlohmann::json& config) {
  if (!config.is_object()) throw std::invalid_argument("config: expected a JSON object");
  for (const auto& [key, value] : config.items()) {
    const ParamField* field = nullptr;
    for (const ParamField& f : kFields)
      if (key == f.name) field = &f;
    if (!field) throw std::invalid_argument("config: unknown key '" + key + "'");
    const auto number = [&, &key = key, &value = value] {
      if (!value.is_number()) throw std::invalid_argument("config: '" + key + "' must be a number");
      return value.get<double>();
    };
    std::visit(Overload{[&](double Params::*m) { p.*m = number(); },
                        [&, &value = value](std::optional<double> Params::*m) {
                          if (value.is_null())
                            p.*m = std::nullopt;
                          else
                            p.*m = number();
                        },
                        [&, &key = key, &value = value](std::uint64_t Params::*m) {
                          if (!value.is_number_integer() || (value.is_number_integer() && !value.is_number_unsigned() &&
                                                             value.get<std::int64_t>() < 0))
                            throw std::invalid_argument("config: '" + key + "' must be a non-negative integer");
                          p.*m = value.get<std::uint64_t>();
                        },
                        [&, &key = key, &value = value](Integrator Params::*m) {
                          if (!value.is_string()) throw std::invalid_argument("config: '" + key + "' must be a string");
                          p.*m = parse_integrator(value.get<std::string>());
                        }},
               field->member);
  }
}

void apply_config_file(Params& p, const std::filesystem::path& file) {
  const std::optional<FileText> text = FileText::read(file);
  if (!text) throw std::invalid_argument(file.string() + ": cannot open config file");
  try {
    apply_json(p, parse_bounded_json(text->view(), JsonLimits{std::size_t{1} << 20, 16}, file.string()));
  } catch (const JsonInputError& e) {
    throw std::invalid_argument(e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file.string() + ": " + e.what());
  }
}

nlohmann::json to_json(const Params& p) {
  nlohmann::json j = nlohmann::json::object();
  for (const ParamField& f : kFields) {
    std::visit(
        Overload{[&](double Params::*m) { j[f.name] = p.*m; }, [&](std::uint64_t Params::*m) { j[f.name] = p.*m; },
                 [&](std::optional<double> Params::*m) {
                   if (p.*m) j[f.name] = *(p.*m);  // absent when unset
                 },
                 [&](Integrator Params::*m) { j[f.name] = to_string(p.*m); }},
        f.member);
  }
  return j;
}

}  // namespace fnet::sim
