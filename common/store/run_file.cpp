#include "common/store/run_file.hpp"

#include <cstdio>
#include <string>

#include "common/store/hdf5_io.hpp"

namespace fnet {
namespace {

using h5::check;

std::string frame_name(std::uint32_t index) {
  char name[16];
  std::snprintf(name, sizeof name, "%06u", index);
  return name;
}

}  // namespace

void write_run_info(hid_t root, const RunInfo& info) {
  for_each_run_info_field(
      [root](const RunInfoField& field, const auto& value) { h5::write_attribute(root, field.attribute, value); },
      info);
}

RunInfo read_run_info(hid_t root, const std::string& where) {
  RunInfo info;
  for_each_run_info_field(
      [&](const RunInfoField& field, auto& value) { h5::read_attribute(root, field.attribute, where, value); }, info);
  return info;
}

void write_frame_header(hid_t group, const FrameHeader& h) {
  h5::write_attribute(group, "frame", h.index);
  h5::write_attribute(group, "step", h.step);
  h5::write_attribute(group, "time", h.time);
  h5::write_attribute(group, "rho", h.rho);
  h5::write_attribute(group, "z", h.z);
}

FrameHeader read_frame_header(hid_t group, const std::string& run_id, const std::string& where) {
  return {run_id,
          h5::read_uint32(group, "frame", where),
          h5::read_uint64(group, "step", where),
          h5::read_double(group, "time", where),
          h5::read_double(group, "rho", where),
          h5::read_double(group, "z", where)};
}

RunFileWriter::RunFileWriter(const std::filesystem::path& path, const RunInfo& info) {
  h5::quiet();
  file_ = h5::File(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create " + path.string());
  h5::Group root(H5Gopen2(file_.get(), "/", H5P_DEFAULT), "open /");
  h5::write_attribute(root.get(), "schema", std::string(kRunFileSchema));
  write_run_info(root.get(), info);
  h5::Group frames(H5Gcreate2(file_.get(), "/frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create /frames");
  check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush");
}

RunFileWriter RunFileWriter::reopen(const std::filesystem::path& path, std::uint32_t keep) {
  h5::quiet();
  RunFileWriter w;
  w.file_ = h5::File(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open " + path.string());
  h5::Group frames(H5Gopen2(w.file_.get(), "/frames", H5P_DEFAULT), path.string() + ": open /frames");
  for (const std::string& name : h5::member_names(frames.get(), path.string() + ": /frames")) {
    if (std::stoul(name) >= keep)
      check(H5Ldelete(frames.get(), name.c_str(), H5P_DEFAULT), "delete frame " + name);
    else
      ++w.frames_;
  }
  check(H5Fflush(w.file_.get(), H5F_SCOPE_GLOBAL), "flush");
  return w;
}

void RunFileWriter::append(const RunFrame& rf) {
  const Frame& f = rf.frame;
  const std::string name = "/frames/" + frame_name(rf.header.index);
  h5::Group g(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create " + name);
  write_frame_header(g.get(), rf.header);
  h5::write_attribute(g.get(), "particle_count", static_cast<std::uint64_t>(f.particle_count));

  std::vector<double> particles;
  particles.reserve(3 * f.particles.size());
  for (const Particle& p : f.particles) particles.insert(particles.end(), {p.x, p.y, p.r});
  std::vector<std::uint32_t> pairs;
  std::vector<double> forces;
  for (const Contact& c : f.contacts) {
    pairs.insert(pairs.end(), {static_cast<std::uint32_t>(c.i), static_cast<std::uint32_t>(c.j)});
    forces.insert(forces.end(), {c.fn, c.ft});
  }
  std::vector<std::uint32_t> wall_particles;
  std::vector<double> wall_forces;
  for (const WallContact& w : rf.wall_contacts) {
    wall_particles.push_back(w.particle);
    wall_forces.insert(wall_forces.end(), {w.fn, w.ft});
  }
  h5::write_array(g.get(), "particles", particles, f.particles.size(), 3);
  h5::write_array(g.get(), "contact_pairs", pairs, f.contacts.size(), 2);
  h5::write_array(g.get(), "contact_forces", forces, f.contacts.size(), 2);
  h5::write_array(g.get(), "wall_contact_particles", wall_particles, wall_particles.size(), 0);
  h5::write_array(g.get(), "wall_contact_forces", wall_forces, wall_particles.size(), 2);
  check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush after " + name);
  ++frames_;
}

RunFileContents read_run_file(const std::filesystem::path& path) {
  h5::quiet();
  const std::string file = path.string();
  h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + file + " (not an HDF5 file?)");
  h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), file + ": open /");
  const std::string schema = h5::read_string(root.get(), "schema", file);
  if (schema != kRunFileSchema) throw h5::Error(file + ": schema '" + schema + "', expected '" + kRunFileSchema + "'");
  RunFileContents out;
  out.info = read_run_info(root.get(), file);

  h5::Group frames(H5Gopen2(f.get(), "/frames", H5P_DEFAULT), file + ": open /frames");
  for (const std::string& name :
       h5::member_names(frames.get(), file + ": /frames")) {  // zero-padded: name order is frame order
    const std::string where = file + ": /frames/" + name;
    h5::Group g(H5Gopen2(frames.get(), name.c_str(), H5P_DEFAULT), where);
    RunFrame rf;
    rf.header = read_frame_header(g.get(), out.info.run_id, where);
    rf.frame.label = frame_label(out.info.run_id, rf.header.index);
    rf.frame.particle_count = h5::read_uint64(g.get(), "particle_count", where);
    const auto particles = h5::read_doubles(g.get(), "particles", 3, where);
    const auto pairs = h5::read_uint32s(g.get(), "contact_pairs", 2, where);
    const auto forces = h5::read_doubles(g.get(), "contact_forces", 2, where);
    const auto wall_particles = h5::read_uint32s(g.get(), "wall_contact_particles", 0, where);
    const auto wall_forces = h5::read_doubles(g.get(), "wall_contact_forces", 2, where);
    if (pairs.size() != forces.size() || wall_forces.size() != 2 * wall_particles.size())
      throw h5::Error(where + ": contact datasets disagree in length");
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
