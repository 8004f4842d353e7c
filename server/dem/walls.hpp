// Rough walls: four rows of touching monodisperse wall particles whose centres form a square ring
// half a wall diameter outside the free interior [0, box]². Each row moves inward as a rigid
// body at v_c during the compression; rows extend past each other at the corners, so the walls
// stay closed as they approach. Wall particles do not interact with each other.
#pragma once

namespace fnet::sim {

struct Simulation;

// Appends the wall particles of s.params (box, wall_diameter) to the body arrays of s; s.n grains
// must already be in place. Sets s.nw.
void add_walls(Simulation& s);

// How far each wall has moved inward; the side of the free interior; ρ = Σ π r² / side².
double wall_offset(const Simulation& s);
double interior_side(const Simulation& s);
double packing_fraction(const Simulation& s);

// Positions and scaled velocities of the wall particles for the current clock.
void place_walls(Simulation& s);

}  // namespace fnet::sim
