// Reading frames from the CSV files fnet exports and experiments and other codes write
// (proto/frames.md):
//   contacts:  header i,j,fn,ft     (0-based particle indices; signed normal force, tangential force)
//          or  header i,j,fx,fy[,fz] (the force on grain i from grain j as a vector, when the header
//                                    has no fn,ft: split along the line of centres, which needs
//                                    particles; fz 0 when absent)
//   particles: header id,x,y,r[,z]  (ids 0..n-1, each exactly once, any row order; a z column makes
//                                    the frame 3D, spheres; without it the frame is 2D, disks)
// Columns may come in any order; extra columns are ignored. Errors name the file and line.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet {

class CsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How a contacts CSV gives the forces: fn,ft, or fx,fy.
enum class ContactForces { magnitudes, vectors };

// A contacts CSV's rows as written: with vectors, each row's fn and ft hold its fx and fy, `fz` its
// fz (empty when the file has no fz column), and `lines` the line of each row (for messages).
struct ContactsCsv {
  ContactForces forces = ContactForces::magnitudes;
  std::vector<Contact> rows;
  std::vector<double> fz;
  std::vector<std::size_t> lines;
};
ContactsCsv read_contacts_table(const std::filesystem::path& path);

// The contacts of a CSV in the fn,ft form; one in the fx,fy form throws (it needs the positions).
std::vector<Contact> read_contacts_csv(const std::filesystem::path& path);

// A particles CSV: its particles (z 0 without a z column) and the dimension its header gives.
struct ParticlesCsv {
  int dimension = 2;
  std::vector<Particle> particles;
};
ParticlesCsv read_particles_table(const std::filesystem::path& path);
std::vector<Particle> read_particles_csv(const std::filesystem::path& path);

// A frame labelled by the contacts file, of the particles' dimension (2 without particles). Without
// particles the particle count is the largest index + 1. Forces given as vectors are split along
// the line of centres (split_contact_force, x_i - x_j from the particles, in 3D with z; without
// particles, or with an index not among them, it throws). The frame is not validated here.
Frame read_frame_csv(const std::filesystem::path& contacts, const std::optional<std::filesystem::path>& particles);

}  // namespace fnet
