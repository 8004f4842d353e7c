// A LAMMPS run followed while LAMMPS writes it (proto/lammps.md, "Following a run"): each frame as
// soon as both of its snapshots are whole (DumpTail), in TIMESTEP order, until the run's log says
// it finished or no snapshot has been completed for the idle timeout.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "server/sources/frame_source.hpp"
#include "server/sources/lammps_input.hpp"

namespace fnet::sources {

struct FollowOptions {
  std::chrono::duration<double> idle_timeout{300.0};
  std::string log;  // LAMMPS's log; empty: none
  std::chrono::duration<double> poll{0.05};
};

// --idle-timeout and --lammps-log as given; usage errors name the flag.
FollowOptions follow_options(const SourceArguments& given);

// The run as a FrameSource whose next() blocks until the next frame is whole or the run ended. Its
// announcement is made once the first frame is whole (its particle count is that frame's). At the
// end, a snapshot cut short or a TIMESTEP in one kind of dump and not in the other throws, after
// every frame before it was returned.
std::unique_ptr<FrameSource> follow_lammps(const LammpsOptions& options, const FollowOptions& follow);

}  // namespace fnet::sources
