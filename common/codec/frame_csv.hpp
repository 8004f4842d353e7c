// Reading frames from the CSV files fnet exports and LAMMPS-side tools write:
//   contacts:  header i,j,fn,ft  (0-based particle indices)
//   particles: header id,x,y,r   (ids 0..n-1, each exactly once, any row order)
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

std::vector<Contact> read_contacts_csv(const std::filesystem::path& path);
std::vector<Particle> read_particles_csv(const std::filesystem::path& path);

// A frame labelled by the contacts file. Without particles the particle count is the largest
// index + 1. The frame is not validated here.
Frame read_frame_csv(const std::filesystem::path& contacts, const std::optional<std::filesystem::path>& particles);

}  // namespace fnet
