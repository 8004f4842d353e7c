// The command line as every fnet program reads it (Boost.Program_options): a word that is no
// option's value is refused, naming the first such word, instead of being dropped. The usual way
// to meet one is a file pattern the shell expanded (--lammps-atoms atoms.*.txt unquoted): dropped,
// the command would run on the pattern's first file alone.
#pragma once

#include <string>
#include <vector>

#include <boost/program_options.hpp>

namespace fnet {

// For a command line parsed without positional options. Throws program_options::error.
inline void refuse_stray_arguments(const boost::program_options::parsed_options& parsed) {
  namespace po = boost::program_options;
  const std::vector<std::string> stray = po::collect_unrecognized(parsed.options, po::include_positional);
  if (stray.empty()) return;
  throw po::error("unexpected argument '" + stray.front() + "'" +
                  (stray.size() > 1 ? " and " + std::to_string(stray.size() - 1) + " more" : std::string()) +
                  ": every value follows its option; quote a file pattern so that the shell does not expand it");
}

}  // namespace fnet
