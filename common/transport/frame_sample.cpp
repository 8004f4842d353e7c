#include "common/transport/frame_sample.hpp"

#include <string>

#include "common/run/particle_columns.hpp"

namespace fnet::dds {

RunFrame decode_frame_sample(const fnet_ForceFrame& s) {
  RunFrame out;
  out.header = {s.run_id, s.frame, s.step, s.time, s.rho, s.z};
  Frame& f = out.frame;
  f.label = frame_label(out.header.run_id, s.frame);
  f.particle_count = s.particle_count;
  const auto bad = [&](const std::string& what) { return FrameError(f.label + ": " + what); };
  f.dimension = s.dimension;
  if (s.contact_pairs._length % 2 != 0 || s.contact_forces._length != s.contact_pairs._length)
    throw bad("contact arrays disagree: " + std::to_string(s.contact_pairs._length) + " indices, " +
              std::to_string(s.contact_forces._length) + " forces (expected 2 per contact each)");
  if (s.wall_contact_forces._length != 2 * s.wall_contact_particles._length)
    throw bad("wall contact arrays disagree: " + std::to_string(s.wall_contact_particles._length) + " particles, " +
              std::to_string(s.wall_contact_forces._length) + " forces");
  if (f.dimension != 2 && f.dimension != 3)
    throw bad("dimension " + std::to_string(f.dimension) + " is neither 2 nor 3");
  if (const std::string wrong =
          set_particles(f, s.particles._buffer, s.particles._length, s.particle_z._buffer, s.particle_z._length);
      !wrong.empty())
    throw bad(wrong);
  f.contacts.resize(s.contact_pairs._length / 2);
  for (std::size_t k = 0; k < f.contacts.size(); ++k)
    f.contacts[k] = {s.contact_pairs._buffer[2 * k], s.contact_pairs._buffer[2 * k + 1],
                     s.contact_forces._buffer[2 * k], s.contact_forces._buffer[2 * k + 1]};
  out.wall_contacts.resize(s.wall_contact_particles._length);
  for (std::size_t k = 0; k < out.wall_contacts.size(); ++k)
    out.wall_contacts[k] = {s.wall_contact_particles._buffer[k], s.wall_contact_forces._buffer[2 * k],
                            s.wall_contact_forces._buffer[2 * k + 1]};
  return out;
}

}  // namespace fnet::dds
