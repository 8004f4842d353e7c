// The run store and publish read: an input of one of the kinds they accept, chosen by its flags,
// and named by --run-id and --ensemble where those are given.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "server/sources/frame_source.hpp"
#include "server/sources/source_kind.hpp"

namespace fnet::sources {

// "(--run-file F | --csv-dir DIR --run-id R)": --run-id after each kind that does not announce.
std::string run_usage(const std::vector<SourceKind>& kinds);

// The kinds' flags, then --run-id and --ensemble.
void add_run_options(const std::vector<SourceKind>& kinds, boost::program_options::options_description& options);

// Checks the choice (usage errors, before any work) and opens the input. Its announcement and
// frames carry the run id given, else the input's own; the announcement the ensemble given, else
// the input's.
std::unique_ptr<FrameSource> open_run(const std::vector<SourceKind>& kinds,
                                      const boost::program_options::variables_map& vm);

}  // namespace fnet::sources
