#include "common/store/run_file_v1.hpp"

#include <utility>

#include "common/store/hdf5_io.hpp"

namespace fnet {

RunFileContents read_run_file_v1(hid_t file, const std::string& where) {
  h5::Group root(H5Gopen2(file, "/", H5P_DEFAULT), where + ": open /");
  RunFileContents out;
  out.info = read_run_info(root.get(), where);
  h5::Group frames(H5Gopen2(file, "/frames", H5P_DEFAULT), where + ": open /frames");
  // Names are zero-padded frame indices: name order is frame order.
  for (const std::string& name : h5::member_names(frames.get(), where + ": /frames")) {
    const std::string at = where + ": /frames/" + name;
    h5::Group g(H5Gopen2(frames.get(), name.c_str(), H5P_DEFAULT), at);
    RunFrame rf;
    rf.header = {out.info.run_id,
                 h5::read_uint32(g.get(), "frame", at),
                 h5::read_uint64(g.get(), "step", at),
                 h5::read_double(g.get(), "time", at),
                 h5::read_double(g.get(), "rho", at),
                 h5::read_double(g.get(), "z", at)};
    rf.frame.label = frame_label(out.info.run_id, rf.header.index);
    rf.frame.particle_count = h5::read_uint64(g.get(), "particle_count", at);
    const auto particles = h5::read_doubles(g.get(), "particles", 3, at);
    const auto pairs = h5::read_uint32s(g.get(), "contact_pairs", 2, at);
    const auto forces = h5::read_doubles(g.get(), "contact_forces", 2, at);
    const auto wall_particles = h5::read_uint32s(g.get(), "wall_contact_particles", 0, at);
    const auto wall_forces = h5::read_doubles(g.get(), "wall_contact_forces", 2, at);
    if (pairs.size() != forces.size() || wall_forces.size() != 2 * wall_particles.size())
      throw h5::Error(at + ": contact datasets disagree in length");
    for (std::size_t k = 0; k < particles.size(); k += 3)
      rf.frame.particles.push_back({particles[k], particles[k + 1], particles[k + 2]});
    for (std::size_t k = 0; k < pairs.size(); k += 2)
      rf.frame.contacts.push_back({pairs[k], pairs[k + 1], forces[k], forces[k + 1]});
    for (std::size_t w = 0; w < wall_particles.size(); ++w)
      rf.wall_contacts.push_back({wall_particles[w], wall_forces[2 * w], wall_forces[2 * w + 1]});
    out.frames.push_back(std::move(rf));
  }
  return out;
}

}  // namespace fnet
