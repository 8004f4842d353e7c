// A LAMMPS run: its per-atom dumps and the local dumps of its pair forces (proto/lammps.md), read
// whole, or followed while LAMMPS writes them (lammps_follow.hpp).
#include <algorithm>
#include <cstdint>

#include <boost/program_options.hpp>

#include "server/sources/lammps_follow.hpp"
#include "server/sources/lammps_input.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

// Every frame is read and checked when the run is opened: a dump at fault stops the command
// before it writes anything.
class LammpsRun final : public FrameSource {
 public:
  explicit LammpsRun(const LammpsOptions& options) {
    const std::vector<DumpSnapshot> atoms = snapshots(options.atoms, DumpKind::atoms);
    const std::vector<DumpSnapshot> pairs = snapshots(options.pairs, DumpKind::entries);
    require_paired(atoms, pairs, options);
    DensityRegion region = DensityRegion::box;
    RunDimension dimension;
    if (!atoms.empty()) {
      const GrainIds grains = grain_ids(atoms.front(), options.wall_types);
      dimension = run_dimension(options, atoms.front());
      for (std::size_t k = 0; k < atoms.size(); ++k) {
        LammpsFrame frame =
            checked_frame(atoms[k], pairs[k], grains, dimension, options, static_cast<std::uint32_t>(k));
        region = frame.region;
        frames_.push_back(std::move(frame.run));
      }
      info_.particles = static_cast<std::uint32_t>(grains.ids.size());
    }
    info_.frames = static_cast<std::uint32_t>(frames_.size());
    info_.config_json = lammps_config(options, dimension, region);
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    if (next_ == frames_.size()) return std::nullopt;
    return std::move(frames_[next_++]);
  }

 private:
  RunInfo info_;
  std::vector<RunFrame> frames_;
  std::size_t next_ = 0;
};

std::unique_ptr<FrameSource> open_lammps(const SourceArguments& given) {
  const LammpsOptions options = lammps_options(given);
  if (given.count("follow")) {
    if (options.rho.rfind("log:", 0) == 0)
      throw boost::program_options::error(
          "--rho log: does not go with --follow (LAMMPS writes its log behind the dumps)");
    return follow_lammps(options, follow_options(given));
  }
  if (given.count("idle-timeout")) throw boost::program_options::error("--idle-timeout needs --follow");
  return std::make_unique<LammpsRun>(options);
}

}  // namespace

std::vector<SourceFlag> lammps_flags(const std::string& value_name) {
  return {{"lammps-atoms", value_name,
           "LAMMPS per-atom dumps (dump custom: id type x y radius|diameter): a file of any number of "
           "snapshots, or a pattern of files (dump.*.txt); gzip-compressed too (proto/lammps.md)"},
          {"lammps-pairs", value_name,
           "LAMMPS local dumps of the pair forces (dump local), matched to the per-atom dumps by TIMESTEP"},
          {"wall-types", "T,...", "atom types that are walls: not grains; their contacts are wall contacts",
           SourceFlag::Path::none, false},
          {"columns", "ROLE=NAME,...",
           "the pair dump's columns: i=,j= and fn=,ft= (signed normal, tangential magnitude) or fnx=,fny=[,fnz=] "
           "and ftx=,fty=[,ftz=] or the total fx=,fy=[,fz=] on atom i (default: proto/lammps.md's lines); wall=ID: "
           "fix wall/gran ID contacts in the per-atom dump",
           SourceFlag::Path::none, false},
          {"check-balance", "TOL",
           "fail when a grain's net contact force exceeds TOL x the mean contact force (needs force vectors)",
           SourceFlag::Path::none, false},
          {"rho", "log:LOG:COLUMN|column:NAME",
           "rho of each frame from the LAMMPS log's thermo output (thermo_style custom step COLUMN) at its "
           "TIMESTEP, or from a per-atom dump column holding one value, in place of the grains' area (volume in 3D) "
           "over the region",
           SourceFlag::Path::none, false},
          {"dimension", "2|3",
           "the run's dimension (default: the dimension command of --lammps-log's log, else 3 when the first "
           "frame's z column varies, 2 otherwise)",
           SourceFlag::Path::none, false},
          {"lammps-log", "LOG",
           "LAMMPS's log (-log LOG): the run's dimension from its dimension command (not with --follow); with "
           "--follow, the input has ended once it says \"Total wall time\"",
           SourceFlag::Path::none, false}};
}

SourceKind lammps_kind() {
  std::vector<SourceFlag> flags = lammps_flags("PATTERN");
  flags.push_back({"follow", "",
                   "follow the dumps while LAMMPS writes them: each frame as soon as both its snapshots are whole, "
                   "until --lammps-log says the run finished or --idle-timeout passes without a new one",
                   SourceFlag::Path::none, false});
  flags.push_back({"idle-timeout", "SECONDS",
                   "with --follow: the input has ended once no snapshot was completed for this long (default 300)",
                   SourceFlag::Path::none, false});
  return {"LAMMPS run", std::move(flags), false, open_lammps};
}

}  // namespace fnet::sources
