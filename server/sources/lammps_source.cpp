// A LAMMPS run: its per-atom dumps and the local dumps of its pair forces (proto/lammps.md).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "server/sources/force_balance.hpp"
#include "server/sources/lammps_frame.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

// Every snapshot the pattern's files hold, by TIMESTEP; a TIMESTEP twice is an error naming both.
std::vector<DumpSnapshot> snapshots(const std::string& pattern, DumpKind kind) {
  std::vector<DumpSnapshot> out;
  for (const std::filesystem::path& file : dump_files(pattern))
    for (DumpSnapshot& s : read_dump(file, kind)) out.push_back(std::move(s));
  std::stable_sort(out.begin(), out.end(),
                   [](const DumpSnapshot& a, const DumpSnapshot& b) { return a.timestep < b.timestep; });
  for (std::size_t k = 1; k < out.size(); ++k)
    if (out[k].timestep == out[k - 1].timestep)
      throw std::runtime_error(out[k].where() + ": TIMESTEP " + std::to_string(out[k].timestep) + " again (first at " +
                               out[k - 1].where() + ")");
  return out;
}

// The first snapshot of `a` without a partner of the same TIMESTEP in `b`.
const DumpSnapshot* unmatched(const std::vector<DumpSnapshot>& a, const std::vector<DumpSnapshot>& b) {
  for (const DumpSnapshot& s : a)
    if (!std::binary_search(b.begin(), b.end(), s,
                            [](const DumpSnapshot& x, const DumpSnapshot& y) { return x.timestep < y.timestep; }))
      return &s;
  return nullptr;
}

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

// Every frame is read and checked when the run is opened: a dump at fault stops the command
// before it writes anything.
class LammpsRun final : public FrameSource {
 public:
  explicit LammpsRun(const SourceArguments& given) {
    const auto option = [&](const char* name) {
      const auto it = given.find(name);
      return it == given.end() ? std::string() : it->second;
    };
    const std::string atoms_pattern = given.at("lammps-atoms"), pairs_pattern = given.at("lammps-pairs");
    const std::vector<int> wall_types =
        option("wall-types").empty() ? std::vector<int>()
                                     : usage("--wall-types", [&] { return parse_wall_types(option("wall-types")); });
    const PairColumns columns = option("columns").empty()
                                    ? default_pair_columns()
                                    : usage("--columns", [&] { return parse_pair_columns(option("columns")); });
    // 0: no check.
    const double tolerance = option("check-balance").empty() ? 0.0 : tolerance_of(option("check-balance"));

    const std::vector<DumpSnapshot> atoms = snapshots(atoms_pattern, DumpKind::atoms);
    const std::vector<DumpSnapshot> pairs = snapshots(pairs_pattern, DumpKind::entries);
    if (const DumpSnapshot* s = unmatched(atoms, pairs))
      throw std::runtime_error(s->where() + ": TIMESTEP " + std::to_string(s->timestep) +
                               " has no snapshot in the pair dumps " + pairs_pattern);
    if (const DumpSnapshot* s = unmatched(pairs, atoms))
      throw std::runtime_error(s->where() + ": TIMESTEP " + std::to_string(s->timestep) +
                               " has no snapshot in the per-atom dumps " + atoms_pattern);
    DensityRegion region = DensityRegion::box;
    if (!atoms.empty()) {
      const GrainIds grains = grain_ids(atoms.front(), wall_types);
      for (std::size_t k = 0; k < atoms.size(); ++k) {
        LammpsFrame frame =
            lammps_frame(atoms[k], pairs[k], grains, columns, wall_types, static_cast<std::uint32_t>(k));
        if (tolerance > 0) check_balance(frame, grains, tolerance);
        region = frame.region;
        frames_.push_back(std::move(frame.run));
      }
      info_.particles = static_cast<std::uint32_t>(grains.ids.size());
    }
    info_.frames = static_cast<std::uint32_t>(frames_.size());
    info_.config_json = nlohmann::json{{"source",
                                        {{"kind", "lammps"},
                                         {"atoms", atoms_pattern},
                                         {"pairs", pairs_pattern},
                                         {"wall_types", wall_types},
                                         {"rho", density_region_name(region)}}}}
                            .dump();
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    if (next_ == frames_.size()) return std::nullopt;
    return std::move(frames_[next_++]);
  }

 private:
  static void check_balance(const LammpsFrame& frame, const GrainIds& grains, double tolerance) {
    const ForceBalance balance = usage("--check-balance", [&] { return force_balance(frame, tolerance); });
    if (balance.unbalanced.empty()) return;
    std::ostringstream out;
    out << frame.where << ": timestep " << frame.run.header.step << ": " << balance.unbalanced.size() << " of "
        << grains.ids.size() << " grains out of force balance by more than " << tolerance
        << " x the mean contact force " << balance.mean_force << " (worst: atom id";
    for (std::size_t k = 0; k < std::min<std::size_t>(5, balance.unbalanced.size()); ++k)
      out << " " << grains.ids[balance.unbalanced[k].grain] << " at " << balance.unbalanced[k].net;
    out << "); a force column read as the wrong quantity? (--columns)";
    throw std::runtime_error(out.str());
  }

  RunInfo info_;
  std::vector<RunFrame> frames_;
  std::size_t next_ = 0;
};

std::unique_ptr<FrameSource> open_lammps(const SourceArguments& given) { return std::make_unique<LammpsRun>(given); }

}  // namespace

SourceKind lammps_kind() {
  return {"LAMMPS run",
          {{"lammps-atoms", "PATTERN",
            "LAMMPS per-atom dumps (dump custom: id type x y radius|diameter): a file of any number of "
            "snapshots, or a pattern of files (dump.*.txt); gzip-compressed too (proto/lammps.md)"},
           {"lammps-pairs", "PATTERN",
            "LAMMPS local dumps of the pair forces (dump local), matched to the per-atom dumps by TIMESTEP"},
           {"wall-types", "T,...", "atom types that are walls: not grains; their contacts are wall contacts",
            SourceFlag::Path::none, false},
           {"columns", "ROLE=NAME,...",
            "the pair dump's columns: i=,j= and fn=,ft= (signed normal, tangential magnitude) or fnx=,fny=[,fnz=] "
            "and ftx=,fty=[,ftz=] or the total fx=,fy=[,fz=] on atom i (default: proto/lammps.md's lines)",
            SourceFlag::Path::none, false},
           {"check-balance", "TOL",
            "fail when a grain's net contact force exceeds TOL x the mean contact force (needs force vectors)",
            SourceFlag::Path::none, false}},
          false,
          open_lammps};
}

}  // namespace fnet::sources
