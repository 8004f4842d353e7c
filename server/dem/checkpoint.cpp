#include "server/dem/checkpoint.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

namespace fnet::sim {
namespace {

constexpr char kMagic[8] = {'F', 'N', 'E', 'T', 'S', 'I', 'M', '1'};

class Writer {
 public:
  explicit Writer(std::ofstream& out) : out_(out) {}
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
    out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
  void string(const std::string& s) {
    value<std::uint64_t>(s.size());
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }

 private:
  std::ofstream& out_;
};

class Reader {
 public:
  Reader(std::ifstream& in, const std::filesystem::path& path) : in_(in), path_(path) {}
  template <class T>
  T value() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  template <class T>
  void vector(std::vector<T>& v) {
    const auto size = value<std::uint64_t>();
    if (size > (std::uint64_t{1} << 34)) fail("implausible array size");
    v.resize(size);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(size * sizeof(T)));
    check();
  }
  std::string string() {
    const auto size = value<std::uint64_t>();
    if (size > (std::uint64_t{1} << 24)) fail("implausible string size");
    std::string s(size, '\0');
    in_.read(s.data(), static_cast<std::streamsize>(size));
    check();
    return s;
  }
  [[noreturn]] void fail(const std::string& what) const { throw CheckpointError(path_.string() + ": " + what); }

 private:
  void check() const {
    if (!in_) fail("truncated or unreadable checkpoint");
  }
  std::ifstream& in_;
  std::filesystem::path path_;
};

// One list of fields for both directions (S is const for saving), so they cannot drift apart.
template <class IO, class S>
void fields(IO& io, S& s) {
  io.vector(s.radius);
  io.vector(s.inv_mass);
  io.vector(s.inv_inertia);
  for (int k = 0; k < kGearOrder; ++k) {
    io.vector(s.x[k]);
    io.vector(s.y[k]);
    io.vector(s.th[k]);
  }
  io.vector(s.fx);
  io.vector(s.fy);
  io.vector(s.torque);
  io.vector(s.wall_x0);
  io.vector(s.wall_y0);
  io.vector(s.wall_dir_x);
  io.vector(s.wall_dir_y);
  io.vector(s.wall_side);
  auto& l = s.list;
  io.vector(l.offset);
  io.vector(l.partner);
  io.vector(l.hx);
  io.vector(l.hy);
  io.vector(l.fn);
  io.vector(l.ft2);
  io.vector(l.meff);
  io.vector(l.touching);
  io.vector(l.x_build);
  io.vector(l.y_build);
}

void save_scalars(Writer& w, const Simulation& s) {
  w.value<std::uint64_t>(s.n);
  w.value<std::uint64_t>(s.nw);
  w.value(static_cast<std::int32_t>(s.phase));
  w.value(s.step);
  w.value(s.compress_step);
  w.value(s.compress_steps);
  w.value<std::uint64_t>(s.next_frame);
  w.value<std::uint8_t>(s.walls_moving);
  w.value(s.grain_area);
  const NeighbourList& l = s.list;
  w.value(l.wall_offset_build);
  w.value(l.skin);
  w.value(l.builds);
  w.value(l.grid_lo);
  w.value(l.cell);
  w.value(l.cells_per_side);
}

void load_scalars(Reader& r, Simulation& s) {
  s.n = r.value<std::uint64_t>();
  s.nw = r.value<std::uint64_t>();
  const auto phase = r.value<std::int32_t>();
  if (phase < 0 || phase > 2) r.fail("bad phase");
  s.phase = static_cast<Phase>(phase);
  s.step = r.value<std::int64_t>();
  s.compress_step = r.value<std::int64_t>();
  s.compress_steps = r.value<std::int64_t>();
  s.next_frame = r.value<std::uint64_t>();
  s.walls_moving = r.value<std::uint8_t>() != 0;
  s.grain_area = r.value<double>();
  NeighbourList& l = s.list;
  l.wall_offset_build = r.value<double>();
  l.skin = r.value<double>();
  l.builds = r.value<std::int64_t>();
  l.grid_lo = r.value<double>();
  l.cell = r.value<double>();
  l.cells_per_side = r.value<std::uint32_t>();
}

}  // namespace

void save_checkpoint(const Simulation& s, const std::string& run_id, const std::filesystem::path& path,
                     const std::string& ensemble) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw CheckpointError(tmp.string() + ": cannot open for writing");
    Writer w(out);
    out.write(kMagic, sizeof kMagic);
    w.string(to_json(s.params).dump());
    w.string(run_id);
    save_scalars(w, s);
    fields(w, s);
    w.string(ensemble);
    out.flush();
    if (!out) throw CheckpointError(tmp.string() + ": write failed");
  }
  std::filesystem::rename(tmp, path);
}

Restored load_checkpoint(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(path.string() + ": cannot open checkpoint");
  Reader r(in, path);
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("not an fnet-simd checkpoint");
  Restored out;
  Simulation& s = out.simulation;
  try {
    apply_json(s.params, nlohmann::json::parse(r.string()));
  } catch (const std::exception& e) {
    r.fail(std::string("bad parameters: ") + e.what());
  }
  s.c = derive(s.params);
  out.run_id = r.string();
  load_scalars(r, s);
  fields(r, s);
  if (in.peek() != std::char_traits<char>::eof()) out.ensemble = r.string();
  const std::size_t bodies = s.n + s.nw;
  if (s.radius.size() != bodies || s.x[0].size() != bodies || s.x[4].size() != s.n || s.list.offset.size() != s.n + 1 ||
      s.list.hx.size() != s.list.partner.size() || s.list.meff.size() != s.list.partner.size())
    r.fail("inconsistent array sizes");
  for (const std::uint32_t j : s.list.partner)
    if (j >= bodies) r.fail("a pair's partner is out of range");
  index_partners(s.list, bodies);  // not saved: derived from the list
  return out;
}

}  // namespace fnet::sim
