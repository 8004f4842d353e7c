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

// Where a snapshot's atoms are, whichever coordinates it holds.
struct AtomColumns {
  std::size_t id = 0;
  std::optional<std::size_t> type, z;
  std::array<std::size_t, 2> position{};
  std::array<bool, 2> scaled{};
  std::size_t size = 0;
  bool diameter = false;
};

AtomColumns atom_columns(const DumpSnapshot& s, const std::vector<int>& wall_types) {
  AtomColumns c;
  c.id = required_column(s, {"id"}, "");
  c.type = s.column("type");
  if (!wall_types.empty() && !c.type) fail(columns_line(s), "no column type, which --wall-types needs");
  const std::array<std::array<const char*, 4>, 2> names{{{"x", "xu", "xs", "xsu"}, {"y", "yu", "ys", "ysu"}}};
  for (std::size_t a = 0; a < 2; ++a) {
    const auto& n = names[a];
    c.position[a] = required_column(s, {n[0], n[1], n[2], n[3]}, "");
    const std::string& chosen = s.columns[c.position[a]];
    c.scaled[a] = chosen == n[2] || chosen == n[3];
  }
  c.z = any_column(s, {"z", "zu", "zs", "zsu"});
  c.size = required_column(s, {"radius", "diameter"}, "");
  c.diameter = s.columns[c.size] == "diameter";
  return c;
}

struct Atom {
  std::array<double, 2> x{};
  double r = 0;
};

Atom atom(const DumpSnapshot& s, const AtomColumns& c, std::size_t row) {
  Atom a;
  for (std::size_t k = 0; k < 2; ++k) {
    const double v = value(s, row, c.position[k]);
    a.x[k] = c.scaled[k] ? s.box.lo[k] + v * (s.box.hi[k] - s.box.lo[k]) : v;
  }
  a.r = value(s, row, c.size) * (c.diameter ? 0.5 : 1.0);
  if (a.r < 0) fail(s.where(row), "a negative " + s.columns[c.size]);
  return a;
}

// The sides of the region the grains are in, on one axis (see lammps_frame's comment).
std::pair<double, double> region_side(std::size_t axis, const DumpBox& box, const std::vector<Particle>& grains,
                                      const std::vector<Atom>& walls, bool& by_walls) {
  if (box.periodic[axis] || grains.empty()) return {box.lo[axis], box.hi[axis]};
  const auto coord = [](const Particle& p, std::size_t a) { return a == 0 ? p.x : p.y; };
  const std::size_t other = 1 - axis;
  double lo_g = std::numeric_limits<double>::infinity(), hi_g = -lo_g, lo_o = lo_g, hi_o = -lo_g;
  for (const Particle& p : grains) {
    lo_g = std::min(lo_g, coord(p, axis));
    hi_g = std::max(hi_g, coord(p, axis));
    lo_o = std::min(lo_o, coord(p, other));
    hi_o = std::max(hi_o, coord(p, other));
  }
  std::optional<double> lo, hi;
  for (const Atom& w : walls) {
    if (w.x[other] < lo_o || w.x[other] > hi_o) continue;
    if (w.x[axis] < lo_g) lo = std::max(lo.value_or(-std::numeric_limits<double>::infinity()), w.x[axis] + w.r);
    if (w.x[axis] > hi_g) hi = std::min(hi.value_or(std::numeric_limits<double>::infinity()), w.x[axis] - w.r);
  }
  if (lo || hi) by_walls = true;
  return {lo.value_or(box.lo[axis]), hi.value_or(box.hi[axis])};
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

namespace {

// The contacts of fix wall/gran ... contacts, from its per-atom array in the per-atom dump: a grain
// whose f_ID[1] is not 0 touches a wall, pushed by the force f_ID[2..4] at the point f_ID[5..7];
// the normal is the line from that point to the grain's centre.
void add_fix_walls(const DumpSnapshot& atoms, const GrainIds& grains, const std::string& fix, bool vectors,
                   LammpsFrame& out) {
  const auto column = [&](int k) {
    const std::string name = "f_" + fix + "[" + std::to_string(k) + "]";
    if (const auto c = atoms.column(name)) return *c;
    fail(columns_line(atoms), "no column " + name + " (--columns wall=" + fix +
                                  " reads fix wall/gran's contacts array from the per-atom dump)");
  };
  const std::size_t touching = column(1), fx = column(2), fy = column(3), fz = column(4), px = column(5),
                    py = column(6);
  const std::size_t id = *atoms.column("id");
  for (std::size_t row = 0; row < atoms.rows(); ++row) {
    const auto g = grains.index.find(atom_id(atoms, row, id));
    if (g == grains.index.end() || value(atoms, row, touching) == 0) continue;
    const Particle& p = out.run.frame.particles[g->second];
    const std::array<double, 3> f{value(atoms, row, fx), value(atoms, row, fy), value(atoms, row, fz)};
    const std::array<double, 2> d{p.x - value(atoms, row, px), p.y - value(atoms, row, py)};
    const double distance = std::hypot(d[0], d[1]);
    if (!(distance > 0)) fail(atoms.where(row), "the wall contact point is the grain's centre");
    const double fn = (f[0] * d[0] + f[1] * d[1]) / distance;
    const double ft = std::hypot(f[0] - fn * d[0] / distance, f[1] - fn * d[1] / distance, f[2]);
    out.run.wall_contacts.push_back({g->second, fn, ft});
    if (vectors) out.wall_forces.push_back({f[0], f[1]});
  }
}

}  // namespace

LammpsFrame lammps_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                         const PairColumns& columns, const std::vector<int>& wall_types, std::uint32_t index) {
  LammpsFrame out;
  out.where = atoms.where();
  RunFrame& run = out.run;
  run.header.index = index;
  run.header.step = atoms.timestep;
  run.header.time = atoms.time.value_or(0.0);
  run.frame.label = "timestep " + std::to_string(atoms.timestep);
  run.frame.particle_count = grains.ids.size();
  run.frame.particles.resize(grains.ids.size());

  // Atoms: grains in their place, walls by id.
  const AtomColumns ac = atom_columns(atoms, wall_types);
  std::vector<bool> seen(grains.ids.size(), false);
  std::unordered_map<std::uint64_t, std::size_t> wall_index;
  std::vector<Atom> walls;
  std::optional<double> z0;
  const double extent = std::max(atoms.box.hi[0] - atoms.box.lo[0], atoms.box.hi[1] - atoms.box.lo[1]);
  for (std::size_t row = 0; row < atoms.rows(); ++row) {
    const std::uint64_t id = atom_id(atoms, row, ac.id);
    const Atom a = atom(atoms, ac, row);
    if (ac.z) {
      const double z = value(atoms, row, *ac.z);
      if (!z0) z0 = z;
      if (std::abs(z - *z0) > 1e-9 * std::max(extent, 1.0))
        fail(atoms.where(row), "atoms at different z: fnet reads 2D dumps (fix enforce2d) only");
    }
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
    run.frame.particles[it->second] = {a.x[0], a.x[1], a.r};
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
      return {Atom{{p.x, p.y}, p.r}, g->second};
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
    const auto [ai, gi] = position(id_i, row);
    const auto [aj, gj] = position(id_j, row);
    if (!gi && !gj) continue;
    // The line of centres from j to i, by the nearest image across a periodic side.
    std::array<double, 2> d{ai.x[0] - aj.x[0], ai.x[1] - aj.x[1]};
    for (std::size_t k = 0; k < 2; ++k)
      if (atoms.box.periodic[k]) {
        const double side = atoms.box.hi[k] - atoms.box.lo[k];
        d[k] -= side * std::round(d[k] / side);
      }
    const double distance = std::hypot(d[0], d[1]);
    const std::array<double, 2> n{distance > 0 ? d[0] / distance : 0.0, distance > 0 ? d[1] / distance : 0.0};
    double fn = 0, ft = 0;
    std::array<double, 2> force{};  // on i
    if (cf[0]) {
      const auto f = vector_of(cf, row);
      const ContactForceParts parts = split_contact_force({d[0], d[1], 0.0}, f);
      fn = parts.fn;
      ft = parts.ft;
      force = {f[0], f[1]};
    } else {
      std::array<double, 2> normal{};
      if (cfn) {
        fn = value(pairs, row, *cfn);
        normal = {fn * n[0], fn * n[1]};
      } else {
        const auto f = vector_of(cn, row);
        fn = f[0] * n[0] + f[1] * n[1];
        normal = {f[0], f[1]};
      }
      if (cft) {
        ft = std::abs(value(pairs, row, *cft));
      } else {
        const auto f = vector_of(ct, row);
        ft = std::hypot(f[0], f[1], f[2]);
        force = {normal[0] + f[0], normal[1] + f[1]};
      }
    }
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
      if (vectors) out.wall_forces.push_back(gi ? force : std::array<double, 2>{-force[0], -force[1]});
    }
  }

  if (!columns.wall_fix.empty()) add_fix_walls(atoms, grains, columns.wall_fix, vectors, out);

  // ρ and Z.
  bool by_walls = false;
  const auto [x0, x1] = region_side(0, atoms.box, run.frame.particles, walls, by_walls);
  const auto [y0, y1] = region_side(1, atoms.box, run.frame.particles, walls, by_walls);
  double area = 0;
  for (const Particle& p : run.frame.particles) area += std::numbers::pi * p.r * p.r;
  const double region = (x1 - x0) * (y1 - y0);
  if (!(region > 0)) fail(atoms.where(), "the region the grains are in has no area");
  run.header.rho = area / region;
  const std::size_t n_grains = grains.ids.size();
  run.header.z = n_grains == 0 ? 0.0 : 2.0 * static_cast<double>(pushing) / static_cast<double>(n_grains);
  out.region = by_walls                                         ? DensityRegion::walls
               : atoms.box.periodic[0] && atoms.box.periodic[1] ? DensityRegion::periodic_box
                                                                : DensityRegion::box;
  return out;
}

}  // namespace fnet::sources
