// A run read through the command line's flags, as fnet-analyze store reads it: for the tests of the
// LAMMPS readers. "@NAME" in an argument is the file NAME of the test's folder.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <gtest/gtest.h>

#include "server/sources/run_source.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::testing {

inline std::unique_ptr<sources::FrameSource> open_run_source(const std::filesystem::path& dir,
                                                             std::vector<std::string> args) {
  namespace po = boost::program_options;
  args.insert(args.end(), {"--run-id", "lmp"});
  for (std::string& a : args) a = a.starts_with("@") ? (dir / a.substr(1)).string() : a;
  const std::vector<sources::SourceKind> kinds = sources::run_kinds();
  po::options_description options;
  sources::add_run_options(kinds, options);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).run(), vm);
  po::notify(vm);
  return sources::open_run(kinds, vm);
}

inline std::vector<RunFrame> read_run_frames(const std::filesystem::path& dir, const std::vector<std::string>& args) {
  const auto source = open_run_source(dir, args);
  std::vector<RunFrame> frames;
  while (auto f = source->next()) frames.push_back(std::move(*f));
  return frames;
}

// The message of the error reading the run throws; a test failure when it throws none.
inline std::string run_error(const std::filesystem::path& dir, const std::vector<std::string>& args) {
  try {
    read_run_frames(dir, args);
  } catch (const std::exception& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << ::testing::PrintToString(args);
  return "";
}

}  // namespace fnet::testing
