// The force-network frame as simulators report it, and its validation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace fnet {

// z is last so that {x, y, r} is a disk of a 2D frame; it is 0 there.
struct Particle {
  double x = 0, y = 0, r = 0;
  double z = 0;
};

// fn is signed as the simulator reports it (a damped spring may be slightly tensile);
// ft is the tangential force magnitude. Force networks use |fn| and |ft|.
struct Contact {
  std::int64_t i = 0, j = 0;
  double fn = 0, ft = 0;
};

struct Frame {
  std::string label;                // names the frame in every message ("frame 12", a file name)
  int dimension = 2;                // 2: disks in the xy plane (every z is 0); 3: spheres
  std::size_t particle_count = 0;   // vertices of the network, rattlers included
  std::vector<Particle> particles;  // empty, or exactly particle_count entries
  std::vector<Contact> contacts;
};

// Thrown for a frame that must be rejected; what() names the frame and the offending entry.
class FrameError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Without a particle table, particle_count is only declared: the grains it counts beyond those in
// contacts are rattlers, each a vertex of both networks and a point of PD0. So that a few bytes of
// input cannot declare billions of them, such a frame declares at most this many particles per
// contact, plus kDeclaredParticlesFloor; a larger one needs its particle table.
inline constexpr std::size_t kDeclaredParticlesPerContact = 16;
inline constexpr std::size_t kDeclaredParticlesFloor = 1024;

// Checks everything the analysis relies on: dimension 2 or 3 (every z is 0 in 2D), finite values,
// non-negative radii, indices in [0, particle_count), no self-contacts, no pair listed twice (in
// either order), a declared particle count within the bound above.
// A frame with no contacts is valid. Throws FrameError on the first problem found.
void validate(const Frame& frame);

// particle_count for a frame read without a particle table: the largest index + 1.
std::size_t implied_particle_count(const std::vector<Contact>& contacts);

}  // namespace fnet
