// fnet-analyze diagram: a frame's persistence diagrams as one JSON object, or as a GUDHI persistence file.
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/codec/diagram_gudhi.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"
#include "common/topology/persistence.hpp"
#include "server/fnet-analyze/commands.hpp"
#include "server/sources/source_kinds.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

int diagram_command(const std::vector<std::string>& args) {
  const std::vector<sources::SourceKind> kinds = sources::frame_kinds();
  po::options_description options(
      "usage: fnet-analyze diagram " + sources::source_usage(kinds) +
      " [--force normal|tangential] [--format json|gudhi [--essential inf|floor]]\n"
      "\n"
      "Prints the frame's diagram document {\"pd0\": [[birth, death], ...], \"pd1\": [...], \"vertices\": N,\n"
      "\"edges\": E, \"triangles\": T}, which 'fnet-analyze distance' reads.\n"
      "Forces are normalized by the frame's mean over contacts with force > 0; the filtration is\n"
      "superlevel (strong forces first) on the flag complex of the contact graph. A point's death\n"
      "is -1 when the class never dies (rattlers give (0, -1)). Points are sorted by birth, then\n"
      "death, both descending.\n"
      "--format gudhi prints the persistence file GUDHI reads instead: lines 'DIM BIRTH DEATH' in sublevel\n"
      "form, (-b, -d) for fnet's (b, d), a class that never dies dying at inf (--essential inf) or at 0\n"
      "(--essential floor, fnet's default convention for distances).\n"
      "\n"
      "options");
  std::string force = "normal";
  std::string format = "json";
  std::string essential = "inf";
  options.add_options()("help,h", "show this help");
  sources::add_source_options(kinds, options);
  options.add_options()("force", po::value(&force)->default_value("normal"),
                        "which force network: normal or tangential");
  options.add_options()("format", po::value(&format)->default_value("json"),
                        "json (the diagram document) or gudhi (a GUDHI persistence file, sublevel form)");
  options.add_options()("essential", po::value(&essential)->default_value("inf"),
                        "with --format gudhi, where a class that never dies dies: inf or floor (at 0)");
  const auto vm = parse_options(options, args);
  if (!vm) return 0;

  const ForceKind kind = named_option("--force", [&] { return parse_force_kind(force); });
  if (format != "json" && format != "gudhi")
    throw po::error("--format: unknown format '" + format + "' (expected json or gudhi)");
  const GudhiEssential never_dies = named_option("--essential", [&] { return parse_gudhi_essential(essential); });
  if (format == "json" && !vm->at("essential").defaulted()) throw po::error("--essential needs --format gudhi");
  const sources::ChosenSource input = sources::choose_source(kinds, *vm);
  // Each stage's input is freed before the next stage runs, so that the next one reuses its memory
  // rather than faulting fresh pages in (a few microseconds each, thousands on a large frame).
  const fnet::FrameDiagrams diagrams = fnet::compute_persistence([&] {
    const fnet::Frame frame = sources::next_frame(*input.open()).frame;
    fnet::validate(frame);
    return fnet::build_network(frame, kind);
  }());
  std::string text;
  if (format == "gudhi") {
    text = fnet::diagram_gudhi_text(diagrams, never_dies);
  } else {
    text = fnet::diagram_document_text(diagrams);
    text += '\n';
  }
  std::cout.write(text.data(), static_cast<std::streamsize>(text.size()));
  return 0;
}

}  // namespace fnet::analyze
