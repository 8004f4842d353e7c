#include "common/store/analysis_store.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

#include "common/codec/run_info_json.hpp"
#include "common/run/particle_columns.hpp"
#include "common/run/run_names.hpp"
#include "common/store/hdf5_io.hpp"

namespace fnet {
namespace {

using h5::check;

constexpr std::size_t kInfoBytes = 16384;              // one run announcement, as JSON
constexpr std::size_t kReasonBytes = 1024;             // one rejection reason
constexpr std::size_t kCounts = 6;                     // vertices, edges, triangles of normal, then tangential
constexpr std::size_t kPointOffsets = 5;               // start of the 4 diagrams in /points, and the end
constexpr std::size_t kSeries = kStoredSeries.size();  // columns of `distances`
// The frame's rows [begin, end) in particles (and particle_z, since fnet-store-3), in the contacts.
constexpr std::size_t kNetworkOffsets = 4;

h5::Datatype fixed_string(std::size_t bytes) {
  h5::Datatype type(H5Tcopy(H5T_C_S1), "H5Tcopy");
  check(H5Tset_size(type.get(), bytes), "H5Tset_size");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "H5Tset_strpad");
  return type;
}

std::vector<char> padded(const std::string& text, std::size_t bytes) {
  std::vector<char> out(bytes, '\0');
  std::memcpy(out.data(), text.data(), std::min(text.size(), bytes));
  return out;
}

std::vector<std::string> read_strings(hid_t file, const char* name, std::size_t bytes, const std::string& where) {
  h5::Dataset set(H5Dopen2(file, name, H5P_DEFAULT), where + ": open " + name);
  const std::size_t rows = h5::row_count(file, name, where);
  h5::check_fits_in_file(set.get(), rows, bytes, name, where);
  std::vector<char> raw(rows * bytes);
  const h5::Datatype type = fixed_string(bytes);
  if (rows) check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), where + ": read " + name);
  std::vector<std::string> out;
  for (std::size_t k = 0; k < rows; ++k) {
    const char* begin = raw.data() + k * bytes;
    out.emplace_back(begin, strnlen(begin, bytes));
  }
  return out;
}

// The first `rows` times of a time column, NaN where the column stops short or was never written
// (stores from before the times were kept).
std::vector<StoreTime> optional_times(hid_t file, const char* name, std::size_t rows, const std::string& where) {
  std::vector<StoreTime> out(rows, NAN);
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return out;
  const std::vector<double> stored = h5::read_doubles(file, name, 0, where);
  std::copy_n(stored.begin(), std::min(rows, stored.size()), out.begin());
  return out;
}

// "a,b,c": offsets as a message names them.
std::string offsets_text(const std::uint64_t* offsets, std::size_t n) {
  std::string out;
  for (std::size_t k = 0; k < n; ++k) out += (k ? "," : "") + std::to_string(offsets[k]);
  return out;
}

// The network of row `row` of an open store, whose frame is `index`; nullopt when not stored.
// A fnet-store-2 store (`v2`) predates 3D frames: no dimension, no particle_z.
std::optional<Frame> network_at(hid_t file, bool v2, std::size_t row, const std::string& run_id, std::uint32_t index,
                                std::uint64_t particle_count, const std::string& where) {
  h5::Dataset flags(H5Dopen2(file, "has_network", H5P_DEFAULT), where + ": open has_network");
  std::uint8_t stored = 0;
  h5::read_rows(flags.get(), H5T_NATIVE_UINT8, &stored, row, 1, 0, where + ": has_network");
  if (!stored) return std::nullopt;
  h5::Dataset offsets(H5Dopen2(file, "network_offsets", H5P_DEFAULT), where + ": open network_offsets");
  std::array<std::uint64_t, kNetworkOffsets> off{};
  h5::read_rows(offsets.get(), H5T_NATIVE_UINT64, off.data(), row, 1, kNetworkOffsets, where + ": network_offsets");
  std::uint8_t dimension = 2;
  if (!v2) {
    h5::Dataset d(H5Dopen2(file, "dimension", H5P_DEFAULT), where + ": open dimension");
    h5::read_rows(d.get(), H5T_NATIVE_UINT8, &dimension, row, 1, 0, where + ": dimension");
  }
  if (off[0] > off[1] || off[2] > off[3])
    throw h5::Error(where + ": frame " + std::to_string(index) + ": network offsets " +
                    offsets_text(off.data(), kNetworkOffsets) + " bound no rows");
  const std::size_t n = off[1] - off[0], m = off[3] - off[2], nz = v2 ? 0 : n;
  std::vector<double> particles(3 * n), z(nz), forces(2 * m);
  std::vector<std::uint32_t> pairs(2 * m);
  h5::Dataset p(H5Dopen2(file, "particles", H5P_DEFAULT), where + ": open particles");
  h5::Dataset cp(H5Dopen2(file, "contact_pairs", H5P_DEFAULT), where + ": open contact_pairs");
  h5::Dataset cf(H5Dopen2(file, "contact_forces", H5P_DEFAULT), where + ": open contact_forces");
  h5::read_rows(p.get(), H5T_NATIVE_DOUBLE, particles.data(), off[0], n, 3, where + ": particles");
  h5::read_rows(cp.get(), H5T_NATIVE_UINT32, pairs.data(), off[2], m, 2, where + ": contact_pairs");
  h5::read_rows(cf.get(), H5T_NATIVE_DOUBLE, forces.data(), off[2], m, 2, where + ": contact_forces");
  if (nz) {
    h5::Dataset pz(H5Dopen2(file, "particle_z", H5P_DEFAULT), where + ": open particle_z");
    h5::read_rows(pz.get(), H5T_NATIVE_DOUBLE, z.data(), off[0], nz, 0, where + ": particle_z");
  }
  Frame f;
  f.label = frame_label(run_id, index);
  f.particle_count = particle_count;
  f.dimension = dimension;
  if (const std::string wrong = set_particles(f, particles.data(), particles.size(), z.data(), z.size());
      !wrong.empty())
    throw h5::Error(where + ": frame " + std::to_string(index) + ": " + wrong);
  f.contacts.reserve(m);
  for (std::size_t k = 0; k < m; ++k) {
    if (pairs[2 * k] >= n || pairs[2 * k + 1] >= n)
      throw h5::Error(where + ": frame " + std::to_string(index) + ": contact " + std::to_string(k) + " joins grains " +
                      std::to_string(pairs[2 * k]) + " and " + std::to_string(pairs[2 * k + 1]) + " of " +
                      std::to_string(n));
    f.contacts.push_back({pairs[2 * k], pairs[2 * k + 1], forces[2 * k], forces[2 * k + 1]});
  }
  return f;
}

// The diagrams of row `row` of an open store, whose frame is `index`: that row's counts and
// offsets, and the points they bound, which must lie in the file.
FrameDiagramSet diagrams_at(hid_t file, std::size_t row, std::uint32_t index, const std::string& where) {
  std::array<std::uint64_t, kCounts> c{};
  std::array<std::uint64_t, kPointOffsets> off{};
  {
    h5::Dataset counts(H5Dopen2(file, "counts", H5P_DEFAULT), where + ": open counts");
    h5::read_rows(counts.get(), H5T_NATIVE_UINT64, c.data(), row, 1, kCounts, where + ": counts");
    h5::Dataset offsets(H5Dopen2(file, "offsets", H5P_DEFAULT), where + ": open offsets");
    h5::read_rows(offsets.get(), H5T_NATIVE_UINT64, off.data(), row, 1, kPointOffsets, where + ": offsets");
  }
  const std::size_t points_rows = h5::row_count(file, "points", where);
  for (std::size_t d = 0; d + 1 < kPointOffsets; ++d)
    if (off[d + 1] < off[d] || off[d + 1] > points_rows)
      throw h5::Error(where + ": frame " + std::to_string(index) + ": offsets " +
                      offsets_text(off.data(), kPointOffsets) + " do not bound rows of points (" +
                      std::to_string(points_rows) + ")");
  std::vector<double> points(2 * (off[kPointOffsets - 1] - off[0]));
  h5::Dataset p(H5Dopen2(file, "points", H5P_DEFAULT), where + ": open points");
  h5::read_rows(p.get(), H5T_NATIVE_DOUBLE, points.data(), off[0], points.size() / 2, 2, where + ": points");
  FrameDiagramSet out;
  const std::array<Diagram*, 4> diagrams{&out.normal.pd0, &out.normal.pd1, &out.tangential.pd0, &out.tangential.pd1};
  for (std::size_t d = 0; d < 4; ++d) {
    diagrams[d]->reserve(off[d + 1] - off[d]);
    for (std::uint64_t k = off[d] - off[0]; k < off[d + 1] - off[0]; ++k)
      diagrams[d]->push_back({points[2 * k], points[2 * k + 1]});
  }
  out.normal.vertices = c[0], out.normal.edges = c[1], out.normal.triangles = c[2];
  out.tangential.vertices = c[3], out.tangential.edges = c[4], out.tangential.triangles = c[5];
  return out;
}

}  // namespace

StoreTime store_time_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::optional<StoreTime> StoredRun::last_activity() const {
  std::optional<StoreTime> latest;
  const auto consider = [&](StoreTime t) {
    if (!std::isnan(t) && (!latest || t > *latest)) latest = t;
  };
  if (has_info) consider(announced_at);
  for (const StoreTime t : committed_at) consider(t);
  for (const StoreTime t : rejected_at) consider(t);
  return latest;
}

std::filesystem::path store_path(const std::filesystem::path& data_dir, const std::string& run_id) {
  return data_dir / (run_id + ".h5");
}

StoreWriter::StoreWriter(const std::filesystem::path& path, const std::string& run_id) : run_id_(run_id) {
  h5::quiet();
  // A store is always written fresh: what an earlier writer left (perhaps killed mid-frame, its
  // SWMR flag still set) is read back and copied, then the copy replaces it atomically.
  const std::filesystem::path fresh = path.string() + ".new";
  try {
    create(path, fresh);
  } catch (...) {
    std::error_code ignored;  // the space it took is given back; the store stays as it was
    std::filesystem::remove(fresh, ignored);
    throw;
  }
}

void StoreWriter::create(const std::filesystem::path& path, const std::filesystem::path& fresh) {
  const std::string& run_id = run_id_;
  std::optional<StoredRun> previous;
  if (std::filesystem::exists(path)) previous = read_store(path);  // throws if unreadable: never overwrite data
  std::filesystem::remove(fresh);
  {
    const h5::PropertyList fapl = h5::latest_format();
    file_ = h5::File(H5Fcreate(fresh.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), "create " + fresh.string());
    h5::Group root(H5Gopen2(file_.get(), "/", H5P_DEFAULT), "open /");
    h5::write_attribute(root.get(), "schema", std::string(kStoreSchema));
    h5::write_attribute(root.get(), "run_id", run_id);
    h5::write_attribute(root.get(), "convention", std::string(kStoreConvention));
    h5::write_attribute(root.get(), "series", stored_series_layout());
    write_provenance(root.get());
    const hid_t f = file_.get();
    h5::create_extendible(f, "announcements", fixed_string(kInfoBytes).get(), 0, 4);
    h5::create_extendible(f, "frame", H5T_NATIVE_UINT32, 0, 256);
    h5::create_extendible(f, "step", H5T_NATIVE_UINT64, 0, 256);
    for (const char* name : {"time", "rho", "z"}) h5::create_extendible(f, name, H5T_NATIVE_DOUBLE, 0, 256);
    h5::create_extendible(f, "previous", H5T_NATIVE_INT64, 0, 256);
    h5::create_extendible(f, "distances", H5T_NATIVE_DOUBLE, kSeries, 256);
    h5::create_extendible(f, "counts", H5T_NATIVE_UINT64, kCounts, 256);
    h5::create_extendible(f, "offsets", H5T_NATIVE_UINT64, kPointOffsets, 256);
    h5::create_extendible(f, "points", H5T_NATIVE_DOUBLE, 2, 8192);
    h5::create_extendible(f, "rejected_frame", H5T_NATIVE_UINT32, 0, 64);
    h5::create_extendible(f, "rejected_reason", fixed_string(kReasonBytes).get(), 0, 64);
    for (const char* name : {"announced_at", "committed_at", "rejected_at"})
      h5::create_extendible(f, name, H5T_NATIVE_DOUBLE, 0, 256);
    h5::create_extendible(f, "has_network", H5T_NATIVE_UINT8, 0, 256);
    h5::create_extendible(f, "network_offsets", H5T_NATIVE_UINT64, kNetworkOffsets, 256);
    h5::create_extendible(f, "dimension", H5T_NATIVE_UINT8, 0, 256);
    h5::create_extendible(f, "particles", H5T_NATIVE_DOUBLE, 3, 4096);
    h5::create_extendible(f, "particle_z", H5T_NATIVE_DOUBLE, 0, 4096);
    h5::create_extendible(f, "contact_pairs", H5T_NATIVE_UINT32, 2, 4096);
    h5::create_extendible(f, "contact_forces", H5T_NATIVE_DOUBLE, 2, 4096);
  }
  for (const char* name : {"announcements",
                           "announced_at",
                           "frame",
                           "step",
                           "time",
                           "rho",
                           "z",
                           "previous",
                           "distances",
                           "counts",
                           "offsets",
                           "points",
                           "committed_at",
                           "rejected_frame",
                           "rejected_reason",
                           "rejected_at",
                           "has_network",
                           "network_offsets",
                           "dimension",
                           "particles",
                           "particle_z",
                           "contact_pairs",
                           "contact_forces"})
    sets_.emplace(name, h5::Dataset(H5Dopen2(file_.get(), name, H5P_DEFAULT), std::string("open ") + name));
  // From here on the file stays valid for readers whatever happens to this process.
  check(H5Fstart_swmr_write(file_.get()), "H5Fstart_swmr_write " + fresh.string());
  if (previous) {
    if (previous->has_info) write_info(previous->info, previous->announced_at);
    // The networks are copied one frame at a time, so that continuing a long run's store never
    // holds all of them.
    std::optional<h5::File> old;
    if (previous->schema != kStoreSchemaV1) old.emplace(h5::open_for_reading(path.string()));
    for (std::size_t k = 0; k < previous->frames.size(); ++k) {
      AnalyzedFrame& f = previous->frames[k];
      if (old && previous->has_network[k])
        if (auto net = network_at(old->get(), previous->schema == kStoreSchemaV2, k, run_id, f.header.index,
                                  f.diagrams.normal.vertices, path.string()))
          f.network = std::make_shared<const Frame>(std::move(*net));
      append(f, previous->committed_at[k]);
      f.network.reset();
    }
    for (std::size_t k = 0; k < previous->rejected.size(); ++k) append(previous->rejected[k], previous->rejected_at[k]);
  }
  std::filesystem::rename(fresh, path);
}

hid_t StoreWriter::set(const char* name) const { return sets_.at(name).get(); }

void StoreWriter::write_info(const RunInfo& info, StoreTime at) {
  const std::string text = to_json(info, JsonText::verbatim).dump();
  if (text.size() > kInfoBytes)
    throw h5::Error("run announcement longer than " + std::to_string(kInfoBytes) + " bytes");
  const auto row = padded(text, kInfoBytes);
  const h5::Datatype type = fixed_string(kInfoBytes);
  h5::append_rows(set("announced_at"), H5T_NATIVE_DOUBLE, &at, 1, 0);
  h5::append_rows(set("announcements"), type.get(), row.data(), 1, 0);
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush");
}

void StoreWriter::append(const AnalyzedFrame& f, StoreTime at) {
  const std::array<const Diagram*, 4> diagrams{&f.diagrams.normal.pd0, &f.diagrams.normal.pd1,
                                               &f.diagrams.tangential.pd0, &f.diagrams.tangential.pd1};
  std::array<std::uint64_t, kPointOffsets> offsets{};
  offsets[0] = h5::row_count(file_.get(), "points", "store");
  std::vector<double> points;
  for (std::size_t d = 0; d < 4; ++d) {
    for (const PersistencePoint& p : *diagrams[d]) points.insert(points.end(), {p.birth, p.death});
    offsets[d + 1] = offsets[0] + points.size() / 2;
  }
  // Points first, the frame index last: a reader trusts a frame only once "frame" covers it.
  h5::append_rows(set("points"), H5T_NATIVE_DOUBLE, points.data(), points.size() / 2, 2);
  const std::array<std::uint64_t, kCounts> counts{f.diagrams.normal.vertices,  f.diagrams.normal.edges,
                                                  f.diagrams.normal.triangles, f.diagrams.tangential.vertices,
                                                  f.diagrams.tangential.edges, f.diagrams.tangential.triangles};
  const std::int64_t previous = f.previous ? static_cast<std::int64_t>(*f.previous) : -1;
  const std::uint8_t has_network = f.network ? 1 : 0;
  std::array<std::uint64_t, kNetworkOffsets> network_offsets{};
  network_offsets[0] = network_offsets[1] = h5::row_count(file_.get(), "particles", "store");
  network_offsets[2] = network_offsets[3] = h5::row_count(file_.get(), "contact_pairs", "store");
  const auto dimension = static_cast<std::uint8_t>(f.dimension);
  if (f.network) {
    const Frame& net = *f.network;
    const ParticleColumns particles = particle_columns(net, true);
    std::vector<double> forces;
    std::vector<std::uint32_t> pairs;
    pairs.reserve(2 * net.contacts.size());
    forces.reserve(2 * net.contacts.size());
    for (const Contact& c : net.contacts) {
      pairs.insert(pairs.end(), {static_cast<std::uint32_t>(c.i), static_cast<std::uint32_t>(c.j)});
      forces.insert(forces.end(), {c.fn, c.ft});
    }
    network_offsets[1] += net.particles.size();
    network_offsets[3] += net.contacts.size();
    h5::append_rows(set("particles"), H5T_NATIVE_DOUBLE, particles.xyr.data(), net.particles.size(), 3);
    h5::append_rows(set("particle_z"), H5T_NATIVE_DOUBLE, particles.z.data(), net.particles.size(), 0);
    h5::append_rows(set("contact_pairs"), H5T_NATIVE_UINT32, pairs.data(), net.contacts.size(), 2);
    h5::append_rows(set("contact_forces"), H5T_NATIVE_DOUBLE, forces.data(), net.contacts.size(), 2);
  }
  h5::append_rows(set("has_network"), H5T_NATIVE_UINT8, &has_network, 1, 0);
  h5::append_rows(set("network_offsets"), H5T_NATIVE_UINT64, network_offsets.data(), 1, kNetworkOffsets);
  h5::append_rows(set("dimension"), H5T_NATIVE_UINT8, &dimension, 1, 0);
  h5::append_rows(set("step"), H5T_NATIVE_UINT64, &f.header.step, 1, 0);
  h5::append_rows(set("time"), H5T_NATIVE_DOUBLE, &f.header.time, 1, 0);
  h5::append_rows(set("rho"), H5T_NATIVE_DOUBLE, &f.header.rho, 1, 0);
  h5::append_rows(set("z"), H5T_NATIVE_DOUBLE, &f.header.z, 1, 0);
  h5::append_rows(set("previous"), H5T_NATIVE_INT64, &previous, 1, 0);
  h5::append_rows(set("distances"), H5T_NATIVE_DOUBLE, f.distances.value.data(), 1, kSeries);
  h5::append_rows(set("counts"), H5T_NATIVE_UINT64, counts.data(), 1, kCounts);
  h5::append_rows(set("offsets"), H5T_NATIVE_UINT64, offsets.data(), 1, kPointOffsets);
  h5::append_rows(set("committed_at"), H5T_NATIVE_DOUBLE, &at, 1, 0);
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush");
  h5::append_rows(set("frame"), H5T_NATIVE_UINT32, &f.header.index, 1, 0);
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush");
  frames_.push_back(f.header.index);
}

std::optional<Frame> StoreWriter::network(std::uint32_t index) const {
  const auto it = std::lower_bound(frames_.begin(), frames_.end(), index);
  if (it == frames_.end() || *it != index)
    throw h5::Error("store of run " + run_id_ + " has no committed frame " + std::to_string(index));
  const std::size_t row = static_cast<std::size_t>(it - frames_.begin());
  h5::Dataset counts(H5Dopen2(file_.get(), "counts", H5P_DEFAULT), "open counts");
  std::array<std::uint64_t, kCounts> c{};
  h5::read_rows(counts.get(), H5T_NATIVE_UINT64, c.data(), row, 1, kCounts, "store of run " + run_id_);
  return network_at(file_.get(), false, row, run_id_, index, c[0], "store of run " + run_id_);
}

FrameDiagramSet StoreWriter::diagrams(std::uint32_t index) const {
  const auto it = std::lower_bound(frames_.begin(), frames_.end(), index);
  if (it == frames_.end() || *it != index)
    throw h5::Error("store of run " + run_id_ + " has no committed frame " + std::to_string(index));
  return diagrams_at(file_.get(), static_cast<std::size_t>(it - frames_.begin()), index, "store of run " + run_id_);
}

void StoreWriter::append(const RejectedFrame& r, StoreTime at) {
  const auto row = padded(r.reason, kReasonBytes);
  const h5::Datatype type = fixed_string(kReasonBytes);
  h5::append_rows(set("rejected_reason"), type.get(), row.data(), 1, 0);
  h5::append_rows(set("rejected_at"), H5T_NATIVE_DOUBLE, &at, 1, 0);
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush");
  h5::append_rows(set("rejected_frame"), H5T_NATIVE_UINT32, &r.index, 1, 0);
  check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush");
  rejected_.push_back(r.index);
}

bool StoreWriter::holds_frame(std::uint32_t index) const {
  return std::binary_search(frames_.begin(), frames_.end(), index);
}

bool StoreWriter::holds_rejection(std::uint32_t index) const {
  return std::find(rejected_.begin(), rejected_.end(), index) != rejected_.end();
}

namespace {

// One committed row of a store as read: pointers into the columns read whole.
struct StoredFrameRow {
  std::uint32_t frame;
  std::int64_t previous;
  std::uint32_t dimension;
  const std::uint64_t* offsets;           // kPointOffsets
  const std::uint64_t* previous_offsets;  // the row before's; null for the first row
  const std::uint64_t* counts;            // kCounts
  const std::uint64_t* network_offsets;   // kNetworkOffsets; null when the network is not stored
};

// Why a committed row cannot be served (empty when it can). The rules a writer keeps: frames
// ascending, `previous` an earlier frame (or -1), every diagram's points a range of `points`
// after the row before's, the network's ranges ordered and as many grains as the network's
// vertices. The ranges' ends were checked against the datasets' extents by the caller.
std::string stored_frame_problem(const StoredFrameRow& r, std::optional<std::uint32_t> frame_before) {
  if (frame_before && r.frame <= *frame_before)
    return "frame indices not ascending (" + std::to_string(*frame_before) + " then " + std::to_string(r.frame) + ")";
  if (r.previous < -1 || r.previous >= static_cast<std::int64_t>(r.frame))
    return "previous frame " + std::to_string(r.previous) + " is not an earlier frame";
  if (r.dimension != 2 && r.dimension != 3) return "dimension " + std::to_string(r.dimension) + ", expected 2 or 3";
  const std::uint64_t start = r.previous_offsets ? r.previous_offsets[kPointOffsets - 1] : 0;
  if (r.offsets[0] < start)
    return "its points start at row " + std::to_string(r.offsets[0]) + ", inside the frame before's (which end at " +
           std::to_string(start) + ")";
  for (std::size_t d = 0; d + 1 < kPointOffsets; ++d)
    if (r.offsets[d + 1] < r.offsets[d])
      return "offsets not ascending (" + std::to_string(r.offsets[d]) + " then " + std::to_string(r.offsets[d + 1]) +
             ")";
  if (const std::uint64_t* n = r.network_offsets) {
    if (n[1] < n[0] || n[3] < n[2])
      return "network_offsets not ordered (" + std::to_string(n[0]) + ", " + std::to_string(n[1]) + ", " +
             std::to_string(n[2]) + ", " + std::to_string(n[3]) + ")";
    if (n[1] - n[0] != r.counts[0])
      return "its network has " + std::to_string(n[1] - n[0]) + " grains, its counts " + std::to_string(r.counts[0]);
  }
  return "";
}

// The column of `distances` holding each entry of kStoredSeries: the store's `series` attribute
// names its columns; stores written before it have the order of kStoredSeries.
std::array<std::size_t, kSeries> series_columns(hid_t root, const std::string& file) {
  std::array<std::size_t, kSeries> column{};
  for (std::size_t c = 0; c < kSeries; ++c) column[c] = c;
  if (H5Aexists(root, "series") <= 0) return column;
  const std::string layout = h5::read_string(root, "series", file);
  std::vector<std::string> keys;
  for (std::size_t at = 0; at <= layout.size();) {
    const std::size_t end = std::min(layout.find(',', at), layout.size());
    keys.push_back(layout.substr(at, end - at));
    at = end + 1;
  }
  std::array<bool, kSeries> seen{};
  if (keys.size() == kSeries)
    for (std::size_t c = 0; c < kSeries; ++c) {
      const auto s = parse_series_key(keys[c]);
      if (!s) break;
      const std::size_t k = stored_series_index(s->metric, s->dim, s->force);
      if (seen[k]) break;
      seen[k] = true;
      column[k] = c;
    }
  if (std::find(seen.begin(), seen.end(), false) != seen.end())
    throw h5::Error(file + ": attribute 'series' is '" + layout + "', expected a permutation of '" +
                    stored_series_layout() + "'");
  return column;
}

}  // namespace

StoredRun read_store(const std::filesystem::path& path) {
  h5::quiet();
  const std::string file = path.string();
  // SWMR read opens a store whose writer is still running, or was killed.
  const h5::File f = h5::open_for_reading(file);
  h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), file + ": open /");
  const std::string schema = h5::read_string(root.get(), "schema", file);
  if (schema != kStoreSchema && schema != kStoreSchemaV2 && schema != kStoreSchemaV1)
    throw h5::Error(file + ": schema '" + schema + "', expected '" + kStoreSchema + "', '" + kStoreSchemaV2 + "' or '" +
                    kStoreSchemaV1 + "'");
  const bool v1 = schema == kStoreSchemaV1;
  const bool v2 = schema == kStoreSchemaV2;
  StoredRun out;
  out.schema = schema;
  out.provenance = read_provenance(root.get(), file);
  const std::string run_id = h5::read_string(root.get(), "run_id", file);
  if (const std::string wrong = run_id_problem(run_id); !wrong.empty()) throw h5::Error(file + ": " + wrong);
  out.info.run_id = run_id;
  const auto announcements = read_strings(f.get(), "announcements", kInfoBytes, file);
  if (!announcements.empty()) {
    try {
      out.info = run_info_from_json(parse_bounded_json(announcements.back(), kAnnouncementJsonLimits, "JSON"));
    } catch (const std::exception& e) {  // JsonInputError, or nlohmann's for a field missing or mistyped
      throw h5::Error(file + ": unreadable run announcement: " + e.what());
    }
    out.has_info = true;
    if (out.info.run_id != run_id)
      throw h5::Error(file + ": its announcement names run '" + out.info.run_id + "', its attribute run_id another");
  }
  const hid_t g = f.get();
  const auto announced_at = optional_times(g, "announced_at", announcements.size(), file);
  if (!announcements.empty()) out.announced_at = announced_at.back();
  const auto frame = h5::read_uint32s(g, "frame", 0, file);
  const auto step = h5::read_uint64s(g, "step", 0, file);
  const auto time = h5::read_doubles(g, "time", 0, file);
  const auto rho = h5::read_doubles(g, "rho", 0, file);
  const auto z = h5::read_doubles(g, "z", 0, file);
  const auto previous = h5::read_int64s(g, "previous", 0, file);
  // Read as uint32 like has_network; a store from before 3D frames holds 2D frames only.
  const auto dimension =
      v1 || v2 ? std::vector<std::uint32_t>(frame.size(), 2) : h5::read_uint32s(g, "dimension", 0, file);
  const auto column_of = series_columns(root.get(), file);
  const auto distances = h5::read_doubles(g, "distances", kSeries, file);
  const auto counts = h5::read_uint64s(g, "counts", kCounts, file);
  const auto offsets = h5::read_uint64s(g, "offsets", kPointOffsets, file);
  const auto points = h5::read_doubles(g, "points", 2, file);
  std::vector<std::uint32_t> has_network;
  std::vector<std::uint64_t> network_offsets;
  std::size_t particle_rows = 0, contact_rows = 0;
  if (!v1) {
    // Read as uint32: the flags are 0 or 1 whatever width HDF5 converts them from.
    has_network = h5::read_uint32s(g, "has_network", 0, file);
    network_offsets = h5::read_uint64s(g, "network_offsets", kNetworkOffsets, file);
    particle_rows = h5::row_count(g, "particles", file);
    if (!v2) particle_rows = std::min(particle_rows, h5::row_count(g, "particle_z", file));
    contact_rows = std::min(h5::row_count(g, "contact_pairs", file), h5::row_count(g, "contact_forces", file));
  }
  // Committed frames: those every column covers (a killed writer may leave some columns longer).
  std::size_t n = frame.size();
  for (const std::size_t len : {step.size(), time.size(), rho.size(), z.size(), previous.size(),
                                distances.size() / kSeries, counts.size() / kCounts, offsets.size() / kPointOffsets})
    n = std::min(n, len);
  n = std::min(n, dimension.size());
  if (!v1) n = std::min({n, has_network.size(), network_offsets.size() / kNetworkOffsets});
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint64_t* off = &offsets[k * kPointOffsets];
    const bool stored = !v1 && has_network[k] != 0;
    const std::uint64_t* net = stored ? &network_offsets[k * kNetworkOffsets] : nullptr;
    if (off[kPointOffsets - 1] > points.size() / 2) break;                // its points never reached the file
    if (net && (net[1] > particle_rows || net[3] > contact_rows)) break;  // its network never reached the file
    const StoredFrameRow row{frame[k],
                             previous[k],
                             dimension[k],
                             off,
                             k ? &offsets[(k - 1) * kPointOffsets] : nullptr,
                             &counts[k * kCounts],
                             stored ? &network_offsets[k * kNetworkOffsets] : nullptr};
    if (const std::string wrong = stored_frame_problem(row, k ? frame[k - 1] : std::optional<std::uint32_t>{});
        !wrong.empty())
      throw h5::Error(file + ": row " + std::to_string(k) + " (frame " + std::to_string(frame[k]) + "): " + wrong);
    AnalyzedFrame a;
    a.header = {out.info.run_id, frame[k], step[k], time[k], rho[k], z[k]};
    if (previous[k] >= 0) a.previous = static_cast<std::uint32_t>(previous[k]);
    a.dimension = static_cast<int>(dimension[k]);
    for (std::size_t c = 0; c < kSeries; ++c) a.distances.value[c] = distances[k * kSeries + column_of[c]];
    std::array<Diagram*, 4> diagrams{&a.diagrams.normal.pd0, &a.diagrams.normal.pd1, &a.diagrams.tangential.pd0,
                                     &a.diagrams.tangential.pd1};
    for (std::size_t d = 0; d < 4; ++d)
      for (std::uint64_t p = off[d]; p < off[d + 1]; ++p) diagrams[d]->push_back({points[2 * p], points[2 * p + 1]});
    const std::uint64_t* c = &counts[k * kCounts];
    a.diagrams.normal.vertices = c[0], a.diagrams.normal.edges = c[1], a.diagrams.normal.triangles = c[2];
    a.diagrams.tangential.vertices = c[3], a.diagrams.tangential.edges = c[4], a.diagrams.tangential.triangles = c[5];
    out.frames.push_back(std::move(a));
    out.has_network.push_back(stored);
  }
  out.committed_at = optional_times(g, "committed_at", out.frames.size(), file);
  const auto rejected_frame = h5::read_uint32s(g, "rejected_frame", 0, file);
  const auto rejected_reason = read_strings(g, "rejected_reason", kReasonBytes, file);
  for (std::size_t k = 0; k < std::min(rejected_frame.size(), rejected_reason.size()); ++k)
    out.rejected.push_back({rejected_frame[k], rejected_reason[k]});
  out.rejected_at = optional_times(g, "rejected_at", out.rejected.size(), file);
  return out;
}

}  // namespace fnet

namespace fnet {

std::optional<Frame> read_network(const std::filesystem::path& path, std::uint32_t index) {
  const StoredRun run = read_store(path);
  const auto it = std::find_if(run.frames.begin(), run.frames.end(),
                               [&](const AnalyzedFrame& f) { return f.header.index == index; });
  if (it == run.frames.end())
    throw h5::Error(path.string() + ": run " + run.info.run_id + " has no committed frame " + std::to_string(index));
  const std::size_t row = static_cast<std::size_t>(it - run.frames.begin());
  if (!run.has_network[row]) return std::nullopt;
  const h5::File f = h5::open_for_reading(path.string());
  return network_at(f.get(), run.schema == kStoreSchemaV2, row, run.info.run_id, index, it->diagrams.normal.vertices,
                    path.string());
}

FrameDiagramSet read_diagrams(const std::filesystem::path& path, std::uint32_t index) {
  h5::quiet();
  const std::string where = path.string();
  const h5::File f = h5::open_for_reading(where);
  // The frame column is written last: its rows are the committed frames, in ascending order.
  const auto frames = h5::read_uint32s(f.get(), "frame", 0, where);
  const auto it = std::lower_bound(frames.begin(), frames.end(), index);
  if (it == frames.end() || *it != index)
    throw h5::Error(where + ": the store has no committed frame " + std::to_string(index));
  return diagrams_at(f.get(), static_cast<std::size_t>(it - frames.begin()), index, where);
}

StoredRun read_store_in_data_dir(const std::filesystem::path& path) {
  const std::string name = path.stem().string();
  if (path.extension() != ".h5" || !run_id_problem(name).empty())
    throw h5::Error(path.string() + ": not a store's file name (RUN.h5, " + run_id_problem(name) + ")");
  StoredRun run = read_store(path);
  if (run.info.run_id != name)
    throw h5::Error(path.string() + ": holds run '" + run.info.run_id + "', not the run its file name says");
  return run;
}

void read_whole_store_in_data_dir(const std::filesystem::path& path) {
  const StoredRun run = read_store_in_data_dir(path);
  if (run.schema == kStoreSchemaV1) return;  // no networks
  const h5::File f = h5::open_for_reading(path.string());
  for (std::size_t row = 0; row < run.frames.size(); ++row)
    if (run.has_network[row])
      network_at(f.get(), run.schema == kStoreSchemaV2, row, run.info.run_id, run.frames[row].header.index,
                 run.frames[row].diagrams.normal.vertices, path.string());
}

}  // namespace fnet
