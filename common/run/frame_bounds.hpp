// What a frame's header and size may be, checked before a frame is analyzed: a frame outside
// them is rejected with a reason naming the run, the frame and the bound, and nothing else is
// lost. The ranges are physical, so that no value can make a series, a curve or a plot
// meaningless; the sizes are fnet-server's bounds on memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/run/run_frame.hpp"

namespace fnet {

// rho is a packing fraction: grains' area (volume) over the space they fill. Grains that do not
// overlap fill less than all of it; soft grains overlap by a small part of their size, never by
// as much again.
inline constexpr double kMaxRho = 2;
// Z = 2 x contacts / grains. A grain touches at most 6 disks or 12 spheres at least as large as
// itself (the kissing numbers), so grains that do not overlap have fewer than 12 (2D) or 24 (3D)
// contacts per grain on average; twice that is left for soft grains.
inline constexpr double kMaxZ = 48;
// Steps are integers a double holds exactly, as every JSON reader (JavaScript's among them) does.
inline constexpr std::uint64_t kMaxStep = std::uint64_t{1} << 53;

// Empty when the header's numbers are usable: rho finite in [0, kMaxRho], z finite in [0, kMaxZ],
// time finite and >= 0, step <= kMaxStep; else what is wrong ("rho = nan is not ...").
std::string header_problem(const FrameHeader& header);

// The bytes a frame holds in memory: each grain declared (with its particle table or not, since
// the analysis keeps a vertex per grain), each contact and each wall contact.
std::size_t frame_bytes(std::size_t grains, std::size_t contacts, std::size_t wall_contacts = 0);

// "12.5 MiB": how messages about sizes write bytes.
std::string mebibytes(std::size_t bytes);

}  // namespace fnet
