// One frame of a LAMMPS run, for the commands that read one (diagram, explain): the snapshot pair
// of a TIMESTEP, numbered and analyzed exactly as store and publish number the run's frames.
#include <algorithm>
#include <charconv>
#include <stdexcept>

#include <boost/program_options.hpp>

#include "server/sources/lammps_input.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

class LammpsOneFrame final : public FrameSource {
 public:
  LammpsOneFrame(const LammpsOptions& options, std::optional<std::uint64_t> timestep) {
    const std::vector<DumpSnapshot> atoms = snapshots(options.atoms, DumpKind::atoms);
    const std::vector<DumpSnapshot> pairs = snapshots(options.pairs, DumpKind::entries);
    if (atoms.empty()) throw std::runtime_error(options.atoms + ": no snapshot");
    const auto at = [&](const std::vector<DumpSnapshot>& s, const std::string& pattern) {
      const std::uint64_t step = timestep.value_or(atoms.front().timestep);
      const auto it = std::find_if(s.begin(), s.end(), [&](const DumpSnapshot& d) { return d.timestep == step; });
      if (it == s.end())
        throw std::runtime_error(pattern + ": no snapshot of TIMESTEP " + std::to_string(step) +
                                 " (--timestep; the first is " + std::to_string(s.front().timestep) + ")");
      return it;
    };
    if (pairs.empty()) throw std::runtime_error(options.pairs + ": no snapshot");
    const auto a = at(atoms, options.atoms);
    const auto p = at(pairs, options.pairs);
    const RunDimension dimension = run_dimension(options, atoms.front());
    LammpsFrame frame = checked_frame(*a, *p, grain_ids(atoms.front(), options.wall_types), dimension, options,
                                      static_cast<std::uint32_t>(a - atoms.begin()));
    info_.frames = 1;
    info_.particles = static_cast<std::uint32_t>(frame.run.frame.particle_count);
    info_.config_json = lammps_config(options, dimension, frame.region);
    frame_ = std::move(frame.run);
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override { return std::exchange(frame_, std::nullopt); }

 private:
  RunInfo info_;
  std::optional<RunFrame> frame_;  // until taken
};

std::optional<std::uint64_t> timestep_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size())
    throw boost::program_options::error("--timestep: \"" + text + "\" is not a TIMESTEP (a whole number >= 0)");
  return value;
}

std::unique_ptr<FrameSource> open_lammps_frame(const SourceArguments& given) {
  return std::make_unique<LammpsOneFrame>(lammps_options(given), timestep_of(flag_value(given, "timestep")));
}

}  // namespace

SourceKind lammps_frame_kind() {
  std::vector<SourceFlag> flags = lammps_flags("FILE");
  flags.push_back({"timestep", "N", "which snapshot of the dumps: its ITEM: TIMESTEP (default: the first)",
                   SourceFlag::Path::none, false});
  return {"LAMMPS frame", std::move(flags), false, open_lammps_frame};
}

}  // namespace fnet::sources
