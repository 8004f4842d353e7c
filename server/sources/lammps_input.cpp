#include "server/sources/lammps_input.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "server/sources/force_balance.hpp"
#include "server/sources/lammps_thermo.hpp"

namespace fnet::sources {

namespace {

double tolerance_of(const std::string& text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !(value > 0) || !std::isfinite(value))
    throw boost::program_options::error("--check-balance: \"" + text + "\" is not a positive number");
  return value;
}

template <class Parse>
auto usage(const std::string& flag, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw boost::program_options::error(flag + ": " + e.what());
  }
}

bool earlier(const DumpSnapshot& a, const DumpSnapshot& b) { return a.timestep < b.timestep; }

// The first snapshot of `a` without a partner of the same TIMESTEP in `b`.
const DumpSnapshot* unmatched(const std::vector<DumpSnapshot>& a, const std::vector<DumpSnapshot>& b) {
  for (const DumpSnapshot& s : a)
    if (!std::binary_search(b.begin(), b.end(), s, earlier)) return &s;
  return nullptr;
}

void check_balance(const LammpsFrame& frame, const GrainIds& grains, double tolerance) {
  const ForceBalance balance = usage("--check-balance", [&] { return force_balance(frame, tolerance); });
  if (balance.unbalanced.empty()) return;
  std::ostringstream out;
  out << frame.where << ": timestep " << frame.run.header.step << ": " << balance.unbalanced.size() << " of "
      << grains.ids.size() << " grains out of force balance by more than " << tolerance << " x the mean contact force "
      << balance.mean_force << " (worst: atom id";
  for (std::size_t k = 0; k < std::min<std::size_t>(5, balance.unbalanced.size()); ++k)
    out << " " << grains.ids[balance.unbalanced[k].grain] << " at " << balance.unbalanced[k].net;
  out << "); a force column read as the wrong quantity? (--columns)";
  throw std::runtime_error(out.str());
}

// The snapshot's value of a per-atom column that holds one value on every row (a per-atom
// variable made of a global one).
double rho_of_column(const DumpSnapshot& atoms, const std::string& name) {
  const auto c = atoms.column(name);
  if (!c)
    throw std::runtime_error(atoms.file + ":" + std::to_string(atoms.first_row_line - 1) + ": no column " + name +
                             " (--rho column:" + name + ")");
  if (atoms.rows() == 0)
    throw std::runtime_error(atoms.where() + ": no atom row to read --rho column:" + name + " from");
  const double value = atoms.at(0, *c);
  for (std::size_t row = 0; row < atoms.rows(); ++row)
    if (!(atoms.at(row, *c) == value) || !std::isfinite(value))
      throw std::runtime_error(atoms.where(row) + ": column " + name +
                               " is not one finite value on every row (--rho column: reads one per snapshot)");
  return value;
}

}  // namespace

std::string flag_value(const SourceArguments& given, const std::string& name) {
  const auto it = given.find(name);
  return it == given.end() ? std::string() : it->second;
}

LammpsOptions lammps_options(const SourceArguments& given) {
  LammpsOptions out;
  out.atoms = given.at("lammps-atoms");
  out.pairs = given.at("lammps-pairs");
  const std::string walls = flag_value(given, "wall-types"), columns = flag_value(given, "columns"),
                    tolerance = flag_value(given, "check-balance");
  if (!walls.empty()) out.wall_types = usage("--wall-types", [&] { return parse_wall_types(walls); });
  out.columns =
      columns.empty() ? default_pair_columns() : usage("--columns", [&] { return parse_pair_columns(columns); });
  if (!tolerance.empty()) out.balance_tolerance = tolerance_of(tolerance);
  out.rho = flag_value(given, "rho");
  if (out.rho.rfind("column:", 0) == 0) {
    out.rho_column = out.rho.substr(7);
    if (out.rho_column.empty()) throw boost::program_options::error("--rho column: names no column");
  } else if (!out.rho.empty()) {
    const std::size_t colon = out.rho.rfind(':');
    if (out.rho.rfind("log:", 0) != 0 || colon <= 4 || colon + 1 == out.rho.size())
      throw boost::program_options::error("--rho: \"" + out.rho + "\" is not log:PATH:COLUMN or column:NAME");
    out.rho_by_step = thermo_column(out.rho.substr(4, colon - 4), out.rho.substr(colon + 1));
  }
  if (const std::string d = flag_value(given, "dimension"); !d.empty())
    out.dimension = usage("--dimension", [&] { return dimension_flag(d); });
  else if (const std::string log = flag_value(given, "lammps-log"); !log.empty() && !given.count("follow"))
    out.dimension = logged_dimension(log);
  return out;
}

std::vector<DumpSnapshot> snapshots(const std::string& pattern, DumpKind kind) {
  std::vector<DumpSnapshot> out;
  for (const std::filesystem::path& file : dump_files(pattern))
    for (DumpSnapshot& s : read_dump(file, kind)) out.push_back(std::move(s));
  std::stable_sort(out.begin(), out.end(), earlier);
  for (std::size_t k = 1; k < out.size(); ++k)
    if (out[k].timestep == out[k - 1].timestep)
      throw std::runtime_error(out[k].where() + ": TIMESTEP " + std::to_string(out[k].timestep) + " again (first at " +
                               out[k - 1].where() + ")");
  return out;
}

void require_paired(const std::vector<DumpSnapshot>& atoms, const std::vector<DumpSnapshot>& pairs,
                    const LammpsOptions& options) {
  if (const DumpSnapshot* s = unmatched(atoms, pairs))
    throw std::runtime_error(s->where() + ": TIMESTEP " + std::to_string(s->timestep) +
                             " has no snapshot in the pair dumps " + options.pairs);
  if (const DumpSnapshot* s = unmatched(pairs, atoms))
    throw std::runtime_error(s->where() + ": TIMESTEP " + std::to_string(s->timestep) +
                             " has no snapshot in the per-atom dumps " + options.atoms);
}

RunDimension run_dimension(const LammpsOptions& options, const DumpSnapshot& first_atoms) {
  return options.dimension ? *options.dimension : dimension_of_first_frame(first_atoms);
}

LammpsFrame checked_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                          const RunDimension& dimension, const LammpsOptions& options, std::uint32_t index) {
  LammpsFrame frame = lammps_frame(atoms, pairs, grains, options.columns, options.wall_types, dimension, index);
  if (options.balance_tolerance > 0) check_balance(frame, grains, options.balance_tolerance);
  if (!options.rho_column.empty()) {
    frame.run.header.rho = rho_of_column(atoms, options.rho_column);
  } else if (!options.rho.empty()) {
    const auto it = options.rho_by_step.find(atoms.timestep);
    if (it == options.rho_by_step.end())
      throw std::runtime_error(atoms.where() + ": TIMESTEP " + std::to_string(atoms.timestep) +
                               " has no thermo row in --rho " + options.rho +
                               " (thermo output at every step the dumps are written)");
    frame.run.header.rho = it->second;
  }
  return frame;
}

std::string lammps_config(const LammpsOptions& options, const RunDimension& dimension, DensityRegion region) {
  return nlohmann::json{{"source",
                         {{"kind", "lammps"},
                          {"atoms", options.atoms},
                          {"pairs", options.pairs},
                          {"wall_types", options.wall_types},
                          {"dimension", dimension.value},
                          {"rho", options.rho.empty() ? std::string(density_region_name(region)) : options.rho}}}}
      // File names and flags are bytes, not always UTF-8: a byte that is not is written as U+FFFD.
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace fnet::sources
