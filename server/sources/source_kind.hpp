// A kind of input as the command line names it: the flags it takes and how it opens. A command
// lists the kinds it accepts (source_kinds.hpp), adds their flags to its options, and opens
// whichever kind the flags given choose, without ever naming one.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "server/sources/frame_source.hpp"

namespace fnet::sources {

struct SourceFlag {
  enum class Path { none, file, directory };

  std::string name;        // without the dashes: "csv-dir"
  std::string value_name;  // in the usage line: "DIR"; empty for a switch, which takes no value
  std::string meaning;     // for --help
  // A path that must exist (a usage error, before any work); anything else the kind checks itself.
  Path path = Path::none;
  bool required = true;  // given whenever the kind is chosen
};

// The values of a kind's flags that were given, by name; a switch that was given maps to "".
using SourceArguments = std::map<std::string, std::string>;

struct SourceKind {
  std::string name;  // as --help names it, after "a" or "the": "run file"
  // flags[0] chooses the kind: no two kinds of a list share it. Other flags may be shared.
  std::vector<SourceFlag> flags;
  // The input records its run's announcement (id, ensemble, parameters); without one the command
  // line names the run (--run-id).
  bool announces = false;
  std::unique_ptr<FrameSource> (*open)(const SourceArguments& given) = nullptr;
};

struct ChosenSource {
  const SourceKind* kind = nullptr;
  SourceArguments given;
  std::unique_ptr<FrameSource> open() const { return kind->open(given); }
};

// "--csv-dir DIR", or "--contacts C.csv [--particles P.csv]": a kind's flags for a usage line.
std::string kind_usage(const SourceKind& kind);
// The kinds' usage: one kind's alone, several as "(A | B)".
std::string source_usage(const std::vector<SourceKind>& kinds);

// Adds each kind's flags to `options`, a flag shared by kinds once. With a single kind its
// choosing flag is required, as any required option, unless the kind marks it not required (a
// command that takes the kind beside inputs of its own).
void add_source_options(const std::vector<SourceKind>& kinds, boost::program_options::options_description& options);

// The kind whose choosing flag was given, with its flags' values. Usage errors, before any work:
// none or several chosen, a required flag missing, another kind's flag given, a path not there.
ChosenSource choose_source(const std::vector<SourceKind>& kinds, const boost::program_options::variables_map& vm);

// "a, b and c" (or "a, b or c" with " or " as `last`).
std::string join_words(const std::vector<std::string>& words, const std::string& last);

}  // namespace fnet::sources
