// Which columns of a LAMMPS local dump hold what fnet reads of a pair, and which atom types are
// walls. The defaults are the columns of the lines proto/lammps.md has a user add to an input.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace fnet::sources {

// The force of a pair is the force on its first atom (i), as LAMMPS's pair/local reports it, in
// one of three forms; the normal force is signed, positive when the grains push apart.
//   total:      f = (fx, fy, fz), the whole pair force; normal = its component along the line of
//               centres, tangential = the rest.
//   components: fn = (fnx, fny, fnz) and ft = (ftx, fty, ftz), or either as a scalar column (fn
//               signed, ft whose magnitude is taken).
// A vector form makes the force vectors known, which the force-balance check needs.
struct PairColumns {
  std::string i = "c_fnet_pair[1]", j = "c_fnet_pair[2]";
  std::string fn, ft;                                      // scalars; empty: not given
  std::array<std::string, 3> fn_vector, ft_vector, total;  // components; [2] may be empty in 2D
  // The ID of a fix wall/gran ... contacts whose per-atom array the per-atom dump holds as
  // f_ID[1] .. f_ID[7]; empty: none. Its columns, as LAMMPS 29 Sep 2021 fills them (checked by
  // tests/server/sources/lammps_wall_test.py): 1 is 1 for a grain touching the wall, 2-4 the force
  // on the grain, 5-7 the contact point.
  std::string wall_fix;
  bool operator==(const PairColumns&) const = default;
};

// The columns of the documented lines: property/local patom1 patom2 as c_fnet_pair[1..2], and
// pair/local fx fy fz p1 p2 p3 as c_fnet_force[1..6] (the normal force vector, then the tangential
// one, for pair_style gran/* and granular alike).
PairColumns default_pair_columns();

// "i=NAME,j=NAME,fn=NAME,ft=NAME" with fnx= fny= fnz= ftx= fty= ftz= or fx= fy= fz= in place of
// fn and ft, and wall=ID: the roles given replace the defaults (i and j keep theirs unless given;
// naming any force role drops every default force column). Throws std::invalid_argument naming what is wrong:
// an unknown role, a role twice, an empty name, a force given in two forms or not at all.
PairColumns parse_pair_columns(std::string_view text);

// "3,4": the atom types that are walls. Throws std::invalid_argument.
std::vector<int> parse_wall_types(std::string_view text);

}  // namespace fnet::sources
