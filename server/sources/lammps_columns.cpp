#include "server/sources/lammps_columns.hpp"

#include <charconv>
#include <map>
#include <stdexcept>

namespace fnet::sources {

namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> out;
  while (true) {
    const std::size_t k = text.find(separator);
    out.push_back(text.substr(0, k));
    if (k == std::string_view::npos) return out;
    text.remove_prefix(k + 1);
  }
}

bool any(const std::array<std::string, 3>& names) {
  return !names[0].empty() || !names[1].empty() || !names[2].empty();
}

}  // namespace

PairColumns default_pair_columns() {
  PairColumns c;
  c.fn_vector = {"c_fnet_force[1]", "c_fnet_force[2]", "c_fnet_force[3]"};
  c.ft_vector = {"c_fnet_force[4]", "c_fnet_force[5]", "c_fnet_force[6]"};
  return c;
}

PairColumns parse_pair_columns(std::string_view text) {
  std::map<std::string, std::string> given;
  for (const std::string_view part : split(text, ',')) {
    const std::size_t eq = part.find('=');
    if (eq == std::string_view::npos) throw std::invalid_argument("\"" + std::string(part) + "\" is not ROLE=NAME");
    const std::string role(part.substr(0, eq)), name(part.substr(eq + 1));
    if (name.empty()) throw std::invalid_argument("no column name for " + role);
    if (!given.emplace(role, name).second) throw std::invalid_argument(role + " given twice");
  }
  PairColumns c = default_pair_columns();
  const bool forces = given.size() > given.count("i") + given.count("j") + given.count("wall");
  if (forces) {
    c.fn_vector = c.ft_vector = {};
  }
  const std::map<std::string, std::string*> roles{{"i", &c.i},
                                                  {"j", &c.j},
                                                  {"fn", &c.fn},
                                                  {"ft", &c.ft},
                                                  {"fnx", &c.fn_vector[0]},
                                                  {"fny", &c.fn_vector[1]},
                                                  {"fnz", &c.fn_vector[2]},
                                                  {"ftx", &c.ft_vector[0]},
                                                  {"fty", &c.ft_vector[1]},
                                                  {"ftz", &c.ft_vector[2]},
                                                  {"fx", &c.total[0]},
                                                  {"fy", &c.total[1]},
                                                  {"fz", &c.total[2]},
                                                  {"wall", &c.wall_fix}};
  for (const auto& [role, name] : given) {
    const auto it = roles.find(role);
    if (it == roles.end())
      throw std::invalid_argument("unknown role " + role +
                                  " (i, j, fn, ft, fnx, fny, fnz, ftx, fty, ftz, fx, fy, fz, wall)");
    *it->second = name;
  }
  const auto whole = [](const std::array<std::string, 3>& v) { return !v[0].empty() && !v[1].empty(); };
  const bool normal = !c.fn.empty() || any(c.fn_vector), tangential = !c.ft.empty() || any(c.ft_vector);
  if (any(c.total)) {
    if (normal || tangential) throw std::invalid_argument("fx, fy, fz go without fn, ft and their components");
    if (!whole(c.total)) throw std::invalid_argument("fx and fy are both needed");
    return c;
  }
  if (!c.fn.empty() && any(c.fn_vector)) throw std::invalid_argument("fn goes without fnx, fny, fnz");
  if (!c.ft.empty() && any(c.ft_vector)) throw std::invalid_argument("ft goes without ftx, fty, ftz");
  if (!normal || !tangential)
    throw std::invalid_argument(
        "the normal and the tangential force are both needed (fn or fnx,fny; ft or ftx,fty; "
        "or the total fx,fy)");
  if (any(c.fn_vector) && !whole(c.fn_vector)) throw std::invalid_argument("fnx and fny are both needed");
  if (any(c.ft_vector) && !whole(c.ft_vector)) throw std::invalid_argument("ftx and fty are both needed");
  return c;
}

std::vector<int> parse_wall_types(std::string_view text) {
  std::vector<int> out;
  for (const std::string_view part : split(text, ',')) {
    int type = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), type);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || type < 1)
      throw std::invalid_argument("\"" + std::string(part) + "\" is not an atom type (a whole number from 1)");
    out.push_back(type);
  }
  return out;
}

}  // namespace fnet::sources
