#include "common/run_file.hpp"

#include <array>
#include <cstdio>
#include <string>

namespace fnet {
namespace {

using h5::check;

// Our exceptions carry the messages; HDF5's own error-stack printing would only add noise.
void quiet_hdf5() {
  static const bool once = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)once;
}

std::string group_name(std::uint32_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "/frames/%06u", index);
  return name;
}

void write_attribute(hid_t obj, const char* name, hid_t type, const void* value) {
  h5::Dataspace space(H5Screate(H5S_SCALAR), "H5Screate");
  h5::Attribute attr(H5Acreate2(obj, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), std::string("create attribute ") + name);
  check(H5Awrite(attr.get(), type, value), std::string("write attribute ") + name);
}
void write_attribute(hid_t obj, const char* name, double v) { write_attribute(obj, name, H5T_NATIVE_DOUBLE, &v); }
void write_attribute(hid_t obj, const char* name, std::uint32_t v) { write_attribute(obj, name, H5T_NATIVE_UINT32, &v); }
void write_attribute(hid_t obj, const char* name, std::uint64_t v) { write_attribute(obj, name, H5T_NATIVE_UINT64, &v); }
// Variable-length UTF-8, which h5py reads as str (fixed-length strings come back as bytes).
void write_attribute(hid_t obj, const char* name, const std::string& v) {
  h5::Datatype type(H5Tcopy(H5T_C_S1), "H5Tcopy");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  const char* text = v.c_str();
  write_attribute(obj, name, type.get(), &text);
}

template <class T>
T read_attribute(hid_t obj, const char* name, hid_t type, const std::string& where) {
  if (H5Aexists(obj, name) <= 0) throw h5::Error(where + ": attribute '" + name + "' missing");
  h5::Attribute attr(H5Aopen(obj, name, H5P_DEFAULT), where + ": open attribute " + name);
  T value{};
  check(H5Aread(attr.get(), type, &value), where + ": read attribute " + name);
  return value;
}
std::string read_string_attribute(hid_t obj, const char* name, const std::string& where) {
  if (H5Aexists(obj, name) <= 0) throw h5::Error(where + ": attribute '" + name + "' missing");
  h5::Attribute attr(H5Aopen(obj, name, H5P_DEFAULT), where + ": open attribute " + name);
  h5::Datatype type(H5Aget_type(attr.get()), where + ": attribute type " + name);
  if (H5Tis_variable_str(type.get()) > 0) {
    char* text = nullptr;
    h5::Datatype mem(H5Tget_native_type(type.get(), H5T_DIR_ASCEND), "native type");
    check(H5Aread(attr.get(), mem.get(), &text), where + ": read attribute " + name);
    std::string out = text ? text : "";
    H5free_memory(text);
    return out;
  }
  std::string out(H5Tget_size(type.get()), '\0');
  check(H5Aread(attr.get(), type.get(), out.data()), where + ": read attribute " + name);
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

// A 2-D (rows x cols) or 1-D (cols == 0) dataset; zero rows are allowed.
void write_array(hid_t group, const char* name, hid_t type, const void* data, std::size_t rows, std::size_t cols) {
  const std::array<hsize_t, 2> dims{rows, cols};
  h5::Dataspace space(H5Screate_simple(cols ? 2 : 1, dims.data(), nullptr), "H5Screate_simple");
  h5::Dataset set(H5Dcreate2(group, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                  std::string("create dataset ") + name);
  if (rows > 0) check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
}

template <class T>
std::vector<T> read_array(hid_t group, const char* name, hid_t type, std::size_t cols, const std::string& where) {
  if (H5Lexists(group, name, H5P_DEFAULT) <= 0) throw h5::Error(where + ": dataset '" + name + "' missing");
  h5::Dataset set(H5Dopen2(group, name, H5P_DEFAULT), where + ": open " + name);
  h5::Dataspace space(H5Dget_space(set.get()), where + ": space of " + name);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (rank != (cols ? 2 : 1) || (cols && dims[1] != cols))
    throw h5::Error(where + ": dataset '" + name + "' has the wrong shape");
  std::vector<T> out(dims[0] * (cols ? cols : 1));
  if (!out.empty()) check(H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), where + ": read " + name);
  return out;
}

}  // namespace

RunFileWriter::RunFileWriter(const std::filesystem::path& path, const RunInfo& info) {
  quiet_hdf5();
  file_ = h5::File(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create " + path.string());
  h5::Group root(H5Gopen2(file_.get(), "/", H5P_DEFAULT), "open /");
  write_attribute(root.get(), "schema", std::string(kRunFileSchema));
  write_attribute(root.get(), "run_id", info.run_id);
  write_attribute(root.get(), "config_json", info.config_json);
  write_attribute(root.get(), "particles", info.particles);
  write_attribute(root.get(), "polydispersity", info.polydispersity);
  write_attribute(root.get(), "friction", info.friction);
  write_attribute(root.get(), "k_n", info.k_n);
  write_attribute(root.get(), "restitution", info.restitution);
  write_attribute(root.get(), "kt_over_kn", info.kt_over_kn);
  write_attribute(root.get(), "compression_speed", info.compression_speed);
  write_attribute(root.get(), "dt", info.dt);
  write_attribute(root.get(), "final_density", info.final_density);
  write_attribute(root.get(), "frames_planned", info.frames);
  write_attribute(root.get(), "seed", info.seed);
  h5::Group frames(H5Gcreate2(file_.get(), "/frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create /frames");
  check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush");
}

RunFileWriter RunFileWriter::reopen(const std::filesystem::path& path, std::uint32_t keep) {
  quiet_hdf5();
  RunFileWriter w;
  w.file_ = h5::File(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open " + path.string());
  h5::Group frames(H5Gopen2(w.file_.get(), "/frames", H5P_DEFAULT), path.string() + ": open /frames");
  H5G_info_t info{};
  check(H5Gget_info(frames.get(), &info), "H5Gget_info");
  std::vector<std::string> drop;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    char name[64] = {};
    H5Lget_name_by_idx(frames.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
    if (std::stoul(name) >= keep) drop.emplace_back(name);
    else ++w.frames_;
  }
  for (const std::string& name : drop) check(H5Ldelete(frames.get(), name.c_str(), H5P_DEFAULT), "delete frame " + name);
  check(H5Fflush(w.file_.get(), H5F_SCOPE_GLOBAL), "flush");
  return w;
}

void RunFileWriter::append(const RunFrame& rf) {
  const Frame& f = rf.frame;
  const std::string name = group_name(rf.header.index);
  h5::Group g(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create " + name);
  write_attribute(g.get(), "frame", rf.header.index);
  write_attribute(g.get(), "step", rf.header.step);
  write_attribute(g.get(), "time", rf.header.time);
  write_attribute(g.get(), "rho", rf.header.rho);
  write_attribute(g.get(), "z", rf.header.z);
  write_attribute(g.get(), "particle_count", static_cast<std::uint64_t>(f.particle_count));

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
  write_array(g.get(), "particles", H5T_NATIVE_DOUBLE, particles.data(), f.particles.size(), 3);
  write_array(g.get(), "contact_pairs", H5T_NATIVE_UINT32, pairs.data(), f.contacts.size(), 2);
  write_array(g.get(), "contact_forces", H5T_NATIVE_DOUBLE, forces.data(), f.contacts.size(), 2);
  write_array(g.get(), "wall_contact_particles", H5T_NATIVE_UINT32, wall_particles.data(), wall_particles.size(), 0);
  write_array(g.get(), "wall_contact_forces", H5T_NATIVE_DOUBLE, wall_forces.data(), wall_particles.size(), 2);
  check(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), "flush after " + name);
  ++frames_;
}

RunFileContents read_run_file(const std::filesystem::path& path) {
  quiet_hdf5();
  const std::string file = path.string();
  h5::File f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + file + " (not an HDF5 file?)");
  h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), file + ": open /");
  const std::string schema = read_string_attribute(root.get(), "schema", file);
  if (schema != kRunFileSchema) throw h5::Error(file + ": schema '" + schema + "', expected '" + kRunFileSchema + "'");
  RunFileContents out;
  RunInfo& i = out.info;
  i.run_id = read_string_attribute(root.get(), "run_id", file);
  i.config_json = read_string_attribute(root.get(), "config_json", file);
  i.particles = read_attribute<std::uint32_t>(root.get(), "particles", H5T_NATIVE_UINT32, file);
  i.polydispersity = read_attribute<double>(root.get(), "polydispersity", H5T_NATIVE_DOUBLE, file);
  i.friction = read_attribute<double>(root.get(), "friction", H5T_NATIVE_DOUBLE, file);
  i.k_n = read_attribute<double>(root.get(), "k_n", H5T_NATIVE_DOUBLE, file);
  i.restitution = read_attribute<double>(root.get(), "restitution", H5T_NATIVE_DOUBLE, file);
  i.kt_over_kn = read_attribute<double>(root.get(), "kt_over_kn", H5T_NATIVE_DOUBLE, file);
  i.compression_speed = read_attribute<double>(root.get(), "compression_speed", H5T_NATIVE_DOUBLE, file);
  i.dt = read_attribute<double>(root.get(), "dt", H5T_NATIVE_DOUBLE, file);
  i.final_density = read_attribute<double>(root.get(), "final_density", H5T_NATIVE_DOUBLE, file);
  i.frames = read_attribute<std::uint32_t>(root.get(), "frames_planned", H5T_NATIVE_UINT32, file);
  i.seed = read_attribute<std::uint64_t>(root.get(), "seed", H5T_NATIVE_UINT64, file);

  h5::Group frames(H5Gopen2(f.get(), "/frames", H5P_DEFAULT), file + ": open /frames");
  H5G_info_t info{};
  check(H5Gget_info(frames.get(), &info), file + ": list /frames");
  for (hsize_t k = 0; k < info.nlinks; ++k) {  // names are zero-padded: name order is frame order
    char name[64] = {};
    H5Lget_name_by_idx(frames.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
    const std::string where = file + ": /frames/" + name;
    h5::Group g(H5Gopen2(frames.get(), name, H5P_DEFAULT), where);
    RunFrame rf;
    rf.header.run_id = i.run_id;
    rf.header.index = read_attribute<std::uint32_t>(g.get(), "frame", H5T_NATIVE_UINT32, where);
    rf.header.step = read_attribute<std::uint64_t>(g.get(), "step", H5T_NATIVE_UINT64, where);
    rf.header.time = read_attribute<double>(g.get(), "time", H5T_NATIVE_DOUBLE, where);
    rf.header.rho = read_attribute<double>(g.get(), "rho", H5T_NATIVE_DOUBLE, where);
    rf.header.z = read_attribute<double>(g.get(), "z", H5T_NATIVE_DOUBLE, where);
    rf.frame.label = frame_label(i.run_id, rf.header.index);
    rf.frame.particle_count = read_attribute<std::uint64_t>(g.get(), "particle_count", H5T_NATIVE_UINT64, where);
    const auto particles = read_array<double>(g.get(), "particles", H5T_NATIVE_DOUBLE, 3, where);
    const auto pairs = read_array<std::uint32_t>(g.get(), "contact_pairs", H5T_NATIVE_UINT32, 2, where);
    const auto forces = read_array<double>(g.get(), "contact_forces", H5T_NATIVE_DOUBLE, 2, where);
    const auto wall_particles = read_array<std::uint32_t>(g.get(), "wall_contact_particles", H5T_NATIVE_UINT32, 0, where);
    const auto wall_forces = read_array<double>(g.get(), "wall_contact_forces", H5T_NATIVE_DOUBLE, 2, where);
    if (pairs.size() != forces.size() || wall_forces.size() != 2 * wall_particles.size())
      throw h5::Error(where + ": contact datasets disagree in length");
    for (std::size_t k3 = 0; k3 < particles.size(); k3 += 3)
      rf.frame.particles.push_back({particles[k3], particles[k3 + 1], particles[k3 + 2]});
    for (std::size_t k2 = 0; k2 < pairs.size(); k2 += 2)
      rf.frame.contacts.push_back({pairs[k2], pairs[k2 + 1], forces[k2], forces[k2 + 1]});
    for (std::size_t w = 0; w < wall_particles.size(); ++w)
      rf.wall_contacts.push_back({wall_particles[w], wall_forces[2 * w], wall_forces[2 * w + 1]});
    out.frames.push_back(std::move(rf));
  }
  return out;
}

}  // namespace fnet
