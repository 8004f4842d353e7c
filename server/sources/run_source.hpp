// Where fnet-analyze's run-level commands read a run from: an HDF5 run file or a CSV folder.
#pragma once

#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/run/run_frame.hpp"

namespace fnet::sources {

struct RunSource {
  std::string run_file, csv_dir, run_id, ensemble;
  void add_options(boost::program_options::options_description& options);
  // Reads the run; the run id is the file's unless --run-id overrides it (required for CSV), and so
  // is its ensemble with --ensemble.
  std::pair<RunInfo, std::vector<RunFrame>> read() const;
};

}  // namespace fnet::sources
