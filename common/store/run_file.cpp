#include "common/store/run_file.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "common/run/particle_columns.hpp"
#include "common/store/hdf5_io.hpp"
#include "common/store/run_file_v1.hpp"

namespace fnet {
namespace {

using h5::check;

// Per frame (one row each); "frame" last, the commit mark.
constexpr const char* kFrameColumns[] = {"step", "time", "rho", "z", "particle_count", "dimension", "offsets"};
// Rows of many frames, located by a frame's "offsets".
// particle_z (since fnet-run-3) has the rows of particles.
constexpr const char* kBulk[] = {
    "particles", "particle_z", "contact_pairs", "contact_forces", "wall_contact_particles", "wall_contact_forces"};
constexpr std::size_t kFrameOffsets = 6;  // begin and end rows in particles, contacts, wall contacts

}  // namespace

void write_run_info(hid_t root, const RunInfo& info) {
  for_each_run_info_field(
      [root](const RunInfoField& field, const auto& value) { h5::write_attribute(root, field.attribute, value); },
      info);
}

RunInfo read_run_info(hid_t root, const std::string& where) {
  RunInfo info;
  for_each_run_info_field(
      [&](const RunInfoField& field, auto& value) {
        if (field.since_v2 && H5Aexists(root, field.attribute) <= 0) return;  // written before version 2
        h5::read_attribute(root, field.attribute, where, value);
      },
      info);
  return info;
}

RunFileWriter::RunFileWriter(const std::filesystem::path& path, const RunInfo& info) { create(path, info); }

void RunFileWriter::create(const std::filesystem::path& path, const RunInfo& info) {
  h5::quiet();
  const h5::PropertyList fapl = h5::latest_format();
  file_ = h5::File(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "create " + path.string());
  const hid_t f = file_.get();
  {
    h5::Group root(H5Gopen2(f, "/", H5P_DEFAULT), "open /");
    h5::write_attribute(root.get(), "schema", std::string(kRunFileSchema));
    write_run_info(root.get(), info);
    write_provenance(root.get());
  }
  h5::create_extendible(f, "frame", H5T_NATIVE_UINT32, 0, 256);
  h5::create_extendible(f, "step", H5T_NATIVE_UINT64, 0, 256);
  for (const char* name : {"time", "rho", "z"}) h5::create_extendible(f, name, H5T_NATIVE_DOUBLE, 0, 256);
  h5::create_extendible(f, "particle_count", H5T_NATIVE_UINT64, 0, 256);
  h5::create_extendible(f, "dimension", H5T_NATIVE_UINT8, 0, 256);
  h5::create_extendible(f, "offsets", H5T_NATIVE_UINT64, kFrameOffsets, 256);
  h5::create_extendible(f, "particles", H5T_NATIVE_DOUBLE, 3, 4096);
  h5::create_extendible(f, "particle_z", H5T_NATIVE_DOUBLE, 0, 4096);
  h5::create_extendible(f, "contact_pairs", H5T_NATIVE_UINT32, 2, 4096);
  h5::create_extendible(f, "contact_forces", H5T_NATIVE_DOUBLE, 2, 4096);
  h5::create_extendible(f, "wall_contact_particles", H5T_NATIVE_UINT32, 0, 1024);
  h5::create_extendible(f, "wall_contact_forces", H5T_NATIVE_DOUBLE, 2, 1024);
  sets_.emplace("frame", h5::Dataset(H5Dopen2(f, "frame", H5P_DEFAULT), "open frame"));
  for (const char* name : kFrameColumns) sets_.emplace(name, h5::Dataset(H5Dopen2(f, name, H5P_DEFAULT), name));
  for (const char* name : kBulk) sets_.emplace(name, h5::Dataset(H5Dopen2(f, name, H5P_DEFAULT), name));
  // From here on the file stays valid for readers (SWMR), whatever happens to this process;
  // no object may be created any more, only these datasets grown.
  check(H5Fstart_swmr_write(f), "H5Fstart_swmr_write " + path.string());
}

RunFileWriter RunFileWriter::reopen(const std::filesystem::path& path, std::uint32_t keep) {
  // A file in SWMR mode cannot be reopened for writing after its writer was killed: the frames
  // to keep are read back and written into a fresh file that replaces it.
  RunFileContents old = read_run_file(path);
  const std::filesystem::path fresh = path.string() + ".new";
  RunFileWriter w;
  w.create(fresh, old.info);
  for (const RunFrame& f : old.frames)
    if (f.header.index < keep) w.append(f);
  std::filesystem::rename(fresh, path);
  return w;
}

hid_t RunFileWriter::set(const char* name) const { return sets_.at(name).get(); }

void RunFileWriter::append(const RunFrame& rf) {
  const Frame& f = rf.frame;
  const ParticleColumns particles = particle_columns(f, true);
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
  const hid_t file = file_.get();
  const auto rows = [&](const char* name) { return static_cast<std::uint64_t>(h5::row_count(file, name, "run file")); };
  const std::array<std::uint64_t, kFrameOffsets> offsets{rows("particles"),
                                                         rows("particles") + f.particles.size(),
                                                         rows("contact_pairs"),
                                                         rows("contact_pairs") + f.contacts.size(),
                                                         rows("wall_contact_particles"),
                                                         rows("wall_contact_particles") + rf.wall_contacts.size()};
  // The bulk first, the frame's own row next, its index last: a reader trusts a frame only once
  // "frame" covers it (a killed writer may leave longer datasets behind).
  h5::append_rows(set("particles"), H5T_NATIVE_DOUBLE, particles.xyr.data(), f.particles.size(), 3);
  h5::append_rows(set("particle_z"), H5T_NATIVE_DOUBLE, particles.z.data(), f.particles.size(), 0);
  h5::append_rows(set("contact_pairs"), H5T_NATIVE_UINT32, pairs.data(), f.contacts.size(), 2);
  h5::append_rows(set("contact_forces"), H5T_NATIVE_DOUBLE, forces.data(), f.contacts.size(), 2);
  h5::append_rows(set("wall_contact_particles"), H5T_NATIVE_UINT32, wall_particles.data(), wall_particles.size(), 0);
  h5::append_rows(set("wall_contact_forces"), H5T_NATIVE_DOUBLE, wall_forces.data(), wall_particles.size(), 2);
  const std::uint64_t particle_count = f.particle_count;
  h5::append_rows(set("step"), H5T_NATIVE_UINT64, &rf.header.step, 1, 0);
  h5::append_rows(set("time"), H5T_NATIVE_DOUBLE, &rf.header.time, 1, 0);
  h5::append_rows(set("rho"), H5T_NATIVE_DOUBLE, &rf.header.rho, 1, 0);
  h5::append_rows(set("z"), H5T_NATIVE_DOUBLE, &rf.header.z, 1, 0);
  const auto dimension = static_cast<std::uint8_t>(f.dimension);
  h5::append_rows(set("particle_count"), H5T_NATIVE_UINT64, &particle_count, 1, 0);
  h5::append_rows(set("dimension"), H5T_NATIVE_UINT8, &dimension, 1, 0);
  h5::append_rows(set("offsets"), H5T_NATIVE_UINT64, offsets.data(), 1, kFrameOffsets);
  check(H5Fflush(file, H5F_SCOPE_LOCAL), "flush");
  h5::append_rows(set("frame"), H5T_NATIVE_UINT32, &rf.header.index, 1, 0);
  check(H5Fflush(file, H5F_SCOPE_LOCAL), "flush");
  ++frames_;
}

RunFileContents read_run_file(const std::filesystem::path& path) {
  h5::quiet();
  const std::string file = path.string();
  if (!std::filesystem::exists(path)) throw h5::Error(file + ": no such file");
  const h5::PropertyList fapl = h5::swmr_read_access();
  // SWMR read opens a file whose writer is still running, or was killed; a file of the first
  // schema predates SWMR (its format cannot be opened so) and opens as a plain file.
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl.get());
  if (id < 0) id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  h5::File f(id, "open " + file + " (not an HDF5 run file?)");
  std::string schema;
  {
    h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), file + ": open /");
    schema = h5::read_string(root.get(), "schema", file);
  }
  if (schema == kRunFileSchemaV1) return read_run_file_v1(f.get(), file);
  if (schema != kRunFileSchema && schema != kRunFileSchemaV2)
    throw h5::Error(file + ": schema '" + schema + "', expected '" + kRunFileSchema + "' (or the older '" +
                    kRunFileSchemaV2 + "' or '" + kRunFileSchemaV1 + "')");
  // fnet-run-2 predates 3D frames: no dimension, no particle_z.
  const bool v2 = schema == kRunFileSchemaV2;
  h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), file + ": open /");
  RunFileContents out;
  out.info = read_run_info(root.get(), file);
  out.provenance = read_provenance(root.get(), file);

  const hid_t g = f.get();
  const auto frame = h5::read_uint32s(g, "frame", 0, file);
  const auto step = h5::read_uint64s(g, "step", 0, file);
  const auto time = h5::read_doubles(g, "time", 0, file);
  const auto rho = h5::read_doubles(g, "rho", 0, file);
  const auto z = h5::read_doubles(g, "z", 0, file);
  const auto particle_count = h5::read_uint64s(g, "particle_count", 0, file);
  const auto offsets = h5::read_uint64s(g, "offsets", kFrameOffsets, file);
  const auto dimension = v2 ? std::vector<std::uint32_t>(frame.size(), 2) : h5::read_uint32s(g, "dimension", 0, file);
  const auto particles = h5::read_doubles(g, "particles", 3, file);
  const auto particle_z = v2 ? std::vector<double>{} : h5::read_doubles(g, "particle_z", 0, file);
  const auto pairs = h5::read_uint32s(g, "contact_pairs", 2, file);
  const auto forces = h5::read_doubles(g, "contact_forces", 2, file);
  const auto wall_particles = h5::read_uint32s(g, "wall_contact_particles", 0, file);
  const auto wall_forces = h5::read_doubles(g, "wall_contact_forces", 2, file);
  // Committed frames: those every column covers.
  std::size_t n = frame.size();
  for (const std::size_t len : {step.size(), time.size(), rho.size(), z.size(), particle_count.size(), dimension.size(),
                                offsets.size() / kFrameOffsets})
    n = std::min(n, len);
  const std::array<std::size_t, kFrameOffsets / 2> available{
      v2 ? particles.size() / 3 : std::min(particles.size() / 3, particle_z.size()),
      std::min(pairs.size(), forces.size()) / 2, std::min(wall_particles.size(), wall_forces.size() / 2)};
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint64_t* o = &offsets[k * kFrameOffsets];
    const std::string where = file + ": frame " + std::to_string(frame[k]);
    for (std::size_t b = 0; b < kFrameOffsets / 2; ++b)
      if (o[2 * b] > o[2 * b + 1] || o[2 * b + 1] > available[b]) throw h5::Error(where + ": offsets out of range");
    RunFrame rf;
    rf.header = {out.info.run_id, frame[k], step[k], time[k], rho[k], z[k]};
    rf.frame.label = frame_label(out.info.run_id, frame[k]);
    rf.frame.particle_count = particle_count[k];
    rf.frame.dimension = static_cast<int>(dimension[k]);
    if (const std::string wrong = set_particles(rf.frame, particles.data() + 3 * o[0], 3 * (o[1] - o[0]),
                                                v2 ? nullptr : particle_z.data() + o[0], v2 ? 0 : o[1] - o[0]);
        !wrong.empty())
      throw h5::Error(where + ": " + wrong);
    for (std::uint64_t r = o[2]; r < o[3]; ++r)
      rf.frame.contacts.push_back({pairs[2 * r], pairs[2 * r + 1], forces[2 * r], forces[2 * r + 1]});
    for (std::uint64_t r = o[4]; r < o[5]; ++r)
      rf.wall_contacts.push_back({wall_particles[r], wall_forces[2 * r], wall_forces[2 * r + 1]});
    out.frames.push_back(std::move(rf));
  }
  return out;
}

}  // namespace fnet
