// fnet-simd's command line: the run's parameters (defaults, then --config, then flags) and every
// other option, checked before anything runs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "server/dem/params.hpp"

namespace fnet::sim {

struct SimdOptions {
  Params params;
  std::string config, export_dir, checkpoint_path, run_id, ensemble, lammps_data, out_file;
  double checkpoint_interval = 60, linger = 0, ack_timeout = 600;
  int domain = 0;
  unsigned threads = 1;
  int events_fd = -1;                                 // set by the ensemble that started this run
  std::vector<std::string> physics_flags;             // the flags of the parameter table, without "--"
  std::vector<boost::program_options::option> given;  // the command line as typed (an ensemble passes it on)
  boost::program_options::variables_map vm;
};

// Prints --help or --version and returns none for them. Throws boost::program_options::error or
// std::invalid_argument naming the flag or value at fault.
std::optional<SimdOptions> parse_simd_options(int argc, char** argv);

}  // namespace fnet::sim
