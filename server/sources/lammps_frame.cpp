#include "server/sources/lammps_frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_set>
#include <utility>

#include "common/topology/contact_force.hpp"

namespace fnet::sources {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw std::runtime_error(where + ": " + what);
}

std::string columns_line(const DumpSnapshot& s) { return s.file + ":" + std::to_string(s.first_row_line - 1); }

// The first of `names` that the snapshot has.
std::optional<std::size_t> any_column(const DumpSnapshot& s, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (const auto c = s.column(name)) return c;
  return std::nullopt;
}

std::size_t required_column(const DumpSnapshot& s, std::initializer_list<const char*> names, const std::string& hint) {
  if (const auto c = any_column(s, names)) return *c;
  std::string list;
  for (const char* name : names) {
    if (!list.empty()) list += " or ";
    list += name;
  }
  fail(columns_line(s), "no column " + list + hint);
}

std::optional<std::size_t> named_column(const DumpSnapshot& s, const std::string& name) {
  if (name.empty()) return std::nullopt;
  if (const auto c = s.column(name)) return c;
  fail(columns_line(s), "no column " + name + " (--columns names the pair dump's columns)");
}

double value(const DumpSnapshot& s, std::size_t row, std::size_t column) {
  const double v = s.at(row, column);
  if (!std::isfinite(v)) fail(s.where(row), "column " + s.columns[column] + " is not a finite number");
  return v;
}

std::uint64_t atom_id(const DumpSnapshot& s, std::size_t row, std::size_t column) {
  const double v = value(s, row, column);
  if (v < 0 || v != std::floor(v) || v > 9.007199254740992e15)
    fail(s.where(row), "column " + s.columns[column] + " is not an atom id");
  return static_cast<std::uint64_t>(v);
}

bool is_wall(const std::vector<int>& wall_types, double type) {
  return std::any_of(wall_types.begin(), wall_types.end(), [&](int t) { return t == type; });
}

// Where a snapshot's atoms are, whichever coordinates it holds: x and y always, z where it has one.
struct AtomColumns {
  std::size_t id = 0;
  std::optional<std::size_t> type;
  std::array<std::optional<std::size_t>, 3> position{};
  std::array<bool, 3> scaled{};
  std::size_t size = 0;
  bool diameter = false;
};

constexpr std::array<std::array<const char*, 4>, 3> kPositionNames{
    {{"x", "xu", "xs", "xsu"}, {"y", "yu", "ys", "ysu"}, {"z", "zu", "zs", "zsu"}}};

AtomColumns atom_columns(const DumpSnapshot& s, const std::vector<int>& wall_types) {
  AtomColumns c;
  c.id = required_column(s, {"id"}, "");
  c.type = s.column("type");
  if (!wall_types.empty() && !c.type) fail(columns_line(s), "no column type, which --wall-types needs");
  for (std::size_t a = 0; a < 3; ++a) {
    const auto& n = kPositionNames[a];
    c.position[a] = a < 2 ? required_column(s, {n[0], n[1], n[2], n[3]}, "") : any_column(s, {n[0], n[1], n[2], n[3]});
    if (!c.position[a]) continue;
    const std::string& chosen = s.columns[*c.position[a]];
    c.scaled[a] = chosen == n[2] || chosen == n[3];
  }
  c.size = required_column(s, {"radius", "diameter"}, "");
  c.diameter = s.columns[c.size] == "diameter";
  return c;
}

struct Atom {
  std::array<double, 3> x{};  // z as the dump holds it (0 without a z column)
  double r = 0;
};

double coordinate(const DumpSnapshot& s, const AtomColumns& c, std::size_t row, std::size_t axis) {
  const double v = value(s, row, *c.position[axis]);
  return c.scaled[axis] ? s.box.lo[axis] + v * (s.box.hi[axis] - s.box.lo[axis]) : v;
}

Atom atom(const DumpSnapshot& s, const AtomColumns& c, std::size_t row) {
  Atom a;
  for (std::size_t k = 0; k < 3; ++k)
    if (c.position[k]) a.x[k] = coordinate(s, c, row, k);
  a.r = value(s, row, c.size) * (c.diameter ? 0.5 : 1.0);
  if (a.r < 0) fail(s.where(row), "a negative " + s.columns[c.size]);
  return a;
}

// How far apart two z may be and still be one plane's: rounding, beside the box's largest side.
double plane_tolerance(const DumpBox& box) {
  double extent = 1.0;
  for (std::size_t k = 0; k < 3; ++k) extent = std::max(extent, box.hi[k] - box.lo[k]);
  return 1e-9 * extent;
}

// The first row whose z differs from the first row's beyond plane_tolerance; none without a z column.
std::optional<std::size_t> row_off_the_plane(const DumpSnapshot& s, const AtomColumns& c) {
  if (!c.position[2] || s.rows() == 0) return std::nullopt;
  const double z0 = coordinate(s, c, 0, 2), tolerance = plane_tolerance(s.box);
  for (std::size_t row = 1; row < s.rows(); ++row)
    if (std::abs(coordinate(s, c, row, 2) - z0) > tolerance) return row;
  return std::nullopt;
}

double coordinate_of(const Particle& p, std::size_t axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

// The sides of the region the grains are in, on one axis of `axes` (see lammps_frame's comment).
std::pair<double, double> region_side(std::size_t axis, std::size_t axes, const DumpBox& box,
                                      const std::vector<Particle>& grains, const std::vector<Atom>& walls,
                                      bool& by_walls) {
  if (box.periodic[axis] || grains.empty()) return {box.lo[axis], box.hi[axis]};
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::array<double, 3> lo_g{kInfinity, kInfinity, kInfinity}, hi_g{-kInfinity, -kInfinity, -kInfinity};
  for (const Particle& p : grains)
    for (std::size_t a = 0; a < axes; ++a) {
      lo_g[a] = std::min(lo_g[a], coordinate_of(p, a));
      hi_g[a] = std::max(hi_g[a], coordinate_of(p, a));
    }
  const auto level = [&](const Atom& w) {
    for (std::size_t a = 0; a < axes; ++a)
      if (a != axis && (w.x[a] < lo_g[a] || w.x[a] > hi_g[a])) return false;
    return true;
  };
  std::optional<double> lo, hi;
  for (const Atom& w : walls) {
    if (!level(w)) continue;
    if (w.x[axis] < lo_g[axis]) lo = std::max(lo.value_or(-kInfinity), w.x[axis] + w.r);
    if (w.x[axis] > hi_g[axis]) hi = std::min(hi.value_or(kInfinity), w.x[axis] - w.r);
  }
  if (lo || hi) by_walls = true;
  return {lo.value_or(box.lo[axis]), hi.value_or(box.hi[axis])};
}

// A grain's share of ρ's numerator: its area in 2D, its volume in 3D.
double grain_measure(double r, int dimension) {
  return dimension == 3 ? 4.0 / 3.0 * std::numbers::pi * r * r * r : std::numbers::pi * r * r;
}

}  // namespace

const char* density_region_name(DensityRegion region) {
  switch (region) {
    case DensityRegion::periodic_box:
      return "periodic box";
    case DensityRegion::walls:
      return "wall atoms";
    case DensityRegion::box:
      return "box";
  }
  return "";
}

GrainIds grain_ids(const DumpSnapshot& atoms, const std::vector<int>& wall_types) {
  const AtomColumns c = atom_columns(atoms, wall_types);
  GrainIds out;
  for (std::size_t row = 0; row < atoms.rows(); ++row)
    if (!c.type || !is_wall(wall_types, value(atoms, row, *c.type))) out.ids.push_back(atom_id(atoms, row, c.id));
  std::sort(out.ids.begin(), out.ids.end());
  for (std::size_t k = 0; k < out.ids.size(); ++k) out.index.emplace(out.ids[k], static_cast<std::uint32_t>(k));
  return out;
}

bool z_varies(const DumpSnapshot& atoms) { return row_off_the_plane(atoms, atom_columns(atoms, {})).has_value(); }

namespace {

// The vector from b to a; across a periodic side, to the nearest image of b.
std::array<double, 3> offset(const std::array<double, 3>& a, const std::array<double, 3>& b, const DumpBox& box) {
  std::array<double, 3> d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  for (std::size_t k = 0; k < 3; ++k)
    if (box.periodic[k]) {
      const double side = box.hi[k] - box.lo[k];
      d[k] -= side * std::round(d[k] / side);
    }
  return d;
}

// The contacts of fix wall/gran ... contacts, from its per-atom array in the per-atom dump: a grain
// whose f_ID[1] is not 0 touches a wall, pushed by the force f_ID[2..4] at the point f_ID[5..7];
// the normal is the line from that point to the grain's centre (in the plane, in 2D).
void add_fix_walls(const DumpSnapshot& atoms, const GrainIds& grains, const std::string& fix, bool vectors,
                   int dimension, LammpsFrame& out) {
  const auto column = [&](int k) {
    const std::string name = "f_" + fix + "[" + std::to_string(k) + "]";
    if (const auto c = atoms.column(name)) return *c;
    fail(columns_line(atoms), "no column " + name + " (--columns wall=" + fix +
                                  " reads fix wall/gran's contacts array from the per-atom dump)");
  };
  const std::size_t touching = column(1);
  const std::array<std::size_t, 3> force{column(2), column(3), column(4)}, point{column(5), column(6), column(7)};
  const std::size_t id = *atoms.column("id");
  for (std::size_t row = 0; row < atoms.rows(); ++row) {
    const auto g = grains.index.find(atom_id(atoms, row, id));
    if (g == grains.index.end() || value(atoms, row, touching) == 0) continue;
    const Particle& p = out.run.frame.particles[g->second];
    std::array<double, 3> f{}, d{};
    const std::array<double, 3> centre{p.x, p.y, p.z};
    for (std::size_t k = 0; k < 3; ++k) {
      f[k] = value(atoms, row, force[k]);
      if (k < static_cast<std::size_t>(dimension)) d[k] = centre[k] - value(atoms, row, point[k]);
    }
    if (!(std::hypot(d[0], d[1], d[2]) > 0)) fail(atoms.where(row), "the wall contact point is the grain's centre");
    const ContactForceParts parts = split_contact_force(d, f);
    out.run.wall_contacts.push_back({g->second, parts.fn, parts.ft});
    if (vectors) out.wall_forces.push_back({f[0], f[1], dimension == 3 ? f[2] : 0.0});
  }
}

}  // namespace

LammpsFrame lammps_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                         const PairColumns& columns, const std::vector<int>& wall_types, const RunDimension& dimension,
                         std::uint32_t index) {
  const bool three = dimension.value == 3;
  LammpsFrame out;
  out.where = atoms.where();
  RunFrame& run = out.run;
  run.header.index = index;
  run.header.step = atoms.timestep;
  run.header.time = atoms.time.value_or(0.0);
  run.frame.label = "timestep " + std::to_string(atoms.timestep);
  run.frame.dimension = dimension.value;
  run.frame.particle_count = grains.ids.size();
  run.frame.particles.resize(grains.ids.size());

  // Atoms: grains in their place, walls by id.
  const AtomColumns ac = atom_columns(atoms, wall_types);
  if (three && !ac.position[2])
    fail(columns_line(atoms),
         "no column z (or zu, zs, zsu), which a 3D run needs (dimension 3 from " + dimension.origin + ")");
  if (!three)
    if (const auto row = row_off_the_plane(atoms, ac))
      fail(atoms.where(*row), "atoms at different z in a 2D run (dimension 2 from " + dimension.origin +
                                  "; --dimension 3 reads a 3D run)");
  std::vector<bool> seen(grains.ids.size(), false);
  std::unordered_map<std::uint64_t, std::size_t> wall_index;
  std::vector<Atom> walls;
  for (std::size_t row = 0; row < atoms.rows(); ++row) {
    const std::uint64_t id = atom_id(atoms, row, ac.id);
    Atom a = atom(atoms, ac, row);
    if (!three) a.x[2] = 0;
    if (ac.type && is_wall(wall_types, value(atoms, row, *ac.type))) {
      if (!wall_index.emplace(id, walls.size()).second)
        fail(atoms.where(row), "atom id " + std::to_string(id) + " twice");
      walls.push_back(a);
      continue;
    }
    const auto it = grains.index.find(id);
    if (it == grains.index.end())
      fail(atoms.where(row), "atom id " + std::to_string(id) + " is not a grain of the first frame");
    if (seen[it->second]) fail(atoms.where(row), "atom id " + std::to_string(id) + " twice");
    seen[it->second] = true;
    run.frame.particles[it->second] = {a.x[0], a.x[1], a.r, a.x[2]};
  }
  for (std::size_t g = 0; g < seen.size(); ++g)
    if (!seen[g]) fail(atoms.where(), "atom id " + std::to_string(grains.ids[g]) + " of the first frame is missing");

  // Pairs.
  const std::size_t ci = *named_column(pairs, columns.i), cj = *named_column(pairs, columns.j);
  const auto cfn = named_column(pairs, columns.fn), cft = named_column(pairs, columns.ft);
  std::array<std::optional<std::size_t>, 3> cn, ct, cf;
  for (std::size_t k = 0; k < 3; ++k) {
    cn[k] = named_column(pairs, columns.fn_vector[k]);
    ct[k] = named_column(pairs, columns.ft_vector[k]);
    cf[k] = named_column(pairs, columns.total[k]);
  }
  const bool vectors = cf[0] || (ct[0] && (cfn || cn[0]));
  const auto vector_of = [&](const std::array<std::optional<std::size_t>, 3>& c, std::size_t row) {
    std::array<double, 3> v{};
    for (std::size_t k = 0; k < 3; ++k)
      if (c[k]) v[k] = value(pairs, row, *c[k]);
    return v;
  };
  const auto position = [&](std::uint64_t id, std::size_t row) -> std::pair<Atom, std::optional<std::uint32_t>> {
    if (const auto g = grains.index.find(id); g != grains.index.end()) {
      const Particle& p = run.frame.particles[g->second];
      return {Atom{{p.x, p.y, p.z}, p.r}, g->second};
    }
    if (const auto w = wall_index.find(id); w != wall_index.end()) return {walls[w->second], std::nullopt};
    fail(pairs.where(row), "atom id " + std::to_string(id) + " is not in the per-atom dump of timestep " +
                               std::to_string(atoms.timestep) + " (" + atoms.where() + ")");
  };
  std::unordered_set<std::uint64_t> grain_pairs;
  std::set<std::pair<std::uint32_t, std::uint64_t>> wall_pairs;
  std::size_t pushing = 0;
  for (std::size_t row = 0; row < pairs.rows(); ++row) {
    const std::uint64_t id_i = atom_id(pairs, row, ci), id_j = atom_id(pairs, row, cj);
    // A grain's contact is with another: a row of one atom twice (a periodic image of itself, in a
    // box too small for its cutoff) is no contact fnet can place.
    if (id_i == id_j) fail(pairs.where(row), "atom id " + std::to_string(id_i) + " paired with itself");
    const auto [ai, gi] = position(id_i, row);
    const auto [aj, gj] = position(id_j, row);
    if (!gi && !gj) continue;
    // The line of centres from j to i (z is 0 in 2D).
    const std::array<double, 3> d = offset(ai.x, aj.x, atoms.box);
    const double distance = std::hypot(d[0], d[1], d[2]);
    std::array<double, 3> n{};
    if (distance > 0)
      for (std::size_t k = 0; k < 3; ++k) n[k] = d[k] / distance;
    double fn = 0, ft = 0;
    std::array<double, 3> force{};  // on i
    if (cf[0]) {
      force = vector_of(cf, row);
      const ContactForceParts parts = split_contact_force(d, force);
      fn = parts.fn;
      ft = parts.ft;
    } else {
      std::array<double, 3> normal{};
      if (cfn) {
        fn = value(pairs, row, *cfn);
        normal = {fn * n[0], fn * n[1], fn * n[2]};
      } else {
        normal = vector_of(cn, row);
        fn = normal[0] * n[0] + normal[1] * n[1] + normal[2] * n[2];
      }
      if (cft) {
        ft = std::abs(value(pairs, row, *cft));
      } else {
        const auto f = vector_of(ct, row);
        ft = std::hypot(f[0], f[1], f[2]);
        force = {normal[0] + f[0], normal[1] + f[1], normal[2] + f[2]};
      }
    }
    if (!three) force[2] = 0;  // the balance of a 2D run is in its plane
    if (gi && gj) {
      const std::uint64_t key = std::uint64_t{std::min(*gi, *gj)} << 32 | std::max(*gi, *gj);
      if (!grain_pairs.insert(key).second) continue;
      run.frame.contacts.push_back({*gi, *gj, fn, ft});
      if (vectors) out.contact_forces.push_back(force);
      pushing += fn > 0;
    } else {
      // A wall contact holds the force on its grain.
      const std::uint32_t grain = gi ? *gi : *gj;
      if (!wall_pairs.emplace(grain, gi ? id_j : id_i).second) continue;
      run.wall_contacts.push_back({grain, fn, ft});
      if (vectors) out.wall_forces.push_back(gi ? force : std::array<double, 3>{-force[0], -force[1], -force[2]});
    }
  }

  if (!columns.wall_fix.empty()) add_fix_walls(atoms, grains, columns.wall_fix, vectors, dimension.value, out);

  // ρ and Z.
  bool by_walls = false;
  const std::size_t axes = three ? 3 : 2;
  double region = 1, grains_measure = 0;
  for (std::size_t axis = 0; axis < axes; ++axis) {
    const auto [lo, hi] = region_side(axis, axes, atoms.box, run.frame.particles, walls, by_walls);
    region *= hi - lo;
  }
  for (const Particle& p : run.frame.particles) grains_measure += grain_measure(p.r, dimension.value);
  if (!(region > 0))
    fail(atoms.where(),
         three ? "the region the grains are in has no volume" : "the region the grains are in has no area");
  run.header.rho = grains_measure / region;
  const std::size_t n_grains = grains.ids.size();
  run.header.z = n_grains == 0 ? 0.0 : 2.0 * static_cast<double>(pushing) / static_cast<double>(n_grains);
  bool periodic = true;
  for (std::size_t axis = 0; axis < axes; ++axis) periodic = periodic && atoms.box.periodic[axis];
  out.region = by_walls ? DensityRegion::walls : periodic ? DensityRegion::periodic_box : DensityRegion::box;
  return out;
}

}  // namespace fnet::sources
