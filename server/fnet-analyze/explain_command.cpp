// fnet-analyze explain: where two frames differ most, term by term of a distance's matching.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/codec/distance_json.hpp"
#include "common/codec/explain_json.hpp"
#include "common/codec/explain_table.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/force_network.hpp"
#include "server/fnet-analyze/commands.hpp"
#include "server/query/loaded_frames.hpp"
#include "server/query/pair_query.hpp"
#include "server/sources/input_paths.hpp"
#include "server/sources/source_kinds.hpp"

namespace po = boost::program_options;

namespace fnet::analyze {

int explain_command(const std::vector<std::string>& args) {
  po::options_description options(
      "usage: fnet-analyze explain (A.csv B.csv [--particles-a PA.csv] [--particles-b PB.csv]\n"
      "                            | --lammps-atoms FILE --lammps-pairs FILE [--timestep A] [--wall-types T,...]\n"
      "                              [--columns ROLE=NAME,...] [--other-timestep B]\n"
      "                              [--other-lammps-atoms FILE --other-lammps-pairs FILE])\n"
      "                            --metric bottleneck|wasserstein1|wasserstein2|wasserstein [--q Q]\n"
      "                            [--dim 0|1] [--force normal|tangential] [--essential floor|sentinel|separate]\n"
      "                            [--k K] [--format table|json]\n"
      "\n"
      "Where frame B differs most from frame A: the K longest terms of the optimal matching behind the\n"
      "distance between their diagrams (for the bottleneck the first term is the one that attains it),\n"
      "each with its two diagram points (or the diagonal) and, per point, the simplices that create and\n"
      "destroy it as grain ids: PD0 born at a grain, killed by a contact (two grains); PD1 born at a\n"
      "contact, filled by a triangle (three grains). A.csv and B.csv are contacts CSVs (i,j,fn,ft); with\n"
      "their particle tables (id,x,y,r) each grain also gets its position. From LAMMPS dumps (proto/lammps.md),\n"
      "frame A is the snapshot pair of --timestep (default: the first) and frame B that of --other-timestep in\n"
      "the same dumps, or in --other-lammps-atoms/--other-lammps-pairs (default: their first); grains are numbered\n"
      "as store numbers them, and have positions. Terms of cost 0 are left out:\n"
      "an unchanged frame has none. JSON (--format json):\n"
      "  {\"value\", \"lower\", \"upper\", \"exact\", \"metric\", \"q\"?, \"dim\", \"force\", \"essential\", \"k\",\n"
      "   \"explain\": [{\"rank\", \"cost\", \"a\": point|null, \"b\": point|null}], \"seconds\"}\n"
      "  point = {\"birth\", \"death\", \"birth_simplex\": simplex, \"death_simplex\": simplex|null},\n"
      "  simplex = {\"grains\": [ids], \"positions\": [[x, y], ...]} (positions only with particle tables;\n"
      "  [x, y, z] each for a 3D frame).\n"
      "\n"
      "options");
  std::string metric, essential = "floor", force = "normal", format = "table", particles_a, particles_b;
  std::vector<std::string> files;
  double q = 0;
  long long dim = kDefaultDim, k = 5;
  options.add_options()("help,h", "show this help")(
      "metric", po::value(&metric)->required(), "bottleneck, wasserstein1, wasserstein2, or wasserstein (with --q)")(
      "q", po::value(&q), "the exponent of --metric wasserstein: a real number >= 1")(
      "dim", po::value(&dim)->default_value(kDefaultDim),
      "which diagram: 0 (pd0) or 1 (pd1); the default is the API's, proto/api.md")(
      "force", po::value(&force)->default_value("normal"), "which force network: normal or tangential")(
      "essential", po::value(&essential)->default_value("floor"),
      "never-dying classes: floor (die at 0), sentinel (death -1 literally), separate (matched among themselves)")(
      "k", po::value(&k)->default_value(5), "how many terms: an integer >= 1")(
      "particles-a", po::value(&particles_a), "particles CSV of frame A (id,x,y,r): positions, and rattlers count")(
      "particles-b", po::value(&particles_b), "particles CSV of frame B")(
      "format", po::value(&format)->default_value("table"), "table or json")("files", po::value(&files),
                                                                             "A.csv B.csv (contacts)");
  sources::SourceKind lammps = sources::lammps_frame_kind();
  lammps.flags.front().required = false;  // explain's own input is the contacts files
  const std::vector<sources::SourceKind> lammps_kinds{lammps};
  sources::add_source_options(lammps_kinds, options);
  options.add_options()("other-timestep", po::value<std::string>(),
                        "frame B's TIMESTEP in the LAMMPS dumps (default with --other-lammps-atoms: the first)")(
      "other-lammps-atoms", po::value<std::string>(), "frame B's per-atom dump, when not in --lammps-atoms")(
      "other-lammps-pairs", po::value<std::string>(), "frame B's pair dump, with --other-lammps-atoms");
  po::positional_options_description positional;
  positional.add("files", 2);
  const auto vm = parse_options(options, args, &positional);
  if (!vm) return 0;
  const bool from_lammps = vm->count("lammps-atoms") > 0;
  if (from_lammps && !files.empty()) throw po::error("give A.csv B.csv or --lammps-atoms, not both");
  if (!from_lammps) {
    for (const char* flag : {"other-timestep", "other-lammps-atoms", "other-lammps-pairs"})
      if (vm->count(flag)) throw po::error(std::string("--") + flag + " goes with --lammps-atoms");
    if (files.size() != 2) throw po::error("two contacts files are required (A.csv B.csv), or --lammps-atoms");
  }
  const MetricChoice choice = metric_option(metric, vm->count("q") ? std::optional(q) : std::nullopt);
  const int d = named_option("--dim", [&] { return check_dim(dim); });
  const ForceKind kind = named_option("--force", [&] { return parse_force_kind(force); });
  const EssentialConvention convention =
      named_option("--essential", [&] { return parse_essential_convention(essential); });
  if (k < 1) throw po::error("--k must be an integer >= 1, got " + std::to_string(k));
  if (format != "table" && format != "json") throw po::error("--format must be table or json, got '" + format + "'");
  for (const std::string& file : files) sources::require_file("contacts file", file);
  if (!particles_a.empty()) sources::require_file("--particles-a", particles_a);
  if (!particles_b.empty()) sources::require_file("--particles-b", particles_b);

  const auto read = [](const std::string& contacts, const std::string& particles) {
    return sources::next_frame(
               *sources::open_frame_files(
                   contacts, particles.empty() ? std::nullopt : std::optional<std::filesystem::path>(particles)))
        .frame;
  };
  Frame a, b;
  if (from_lammps) {
    if (!particles_a.empty() || !particles_b.empty())
      throw po::error("--particles-a and --particles-b go with contacts files; LAMMPS frames have positions");
    const sources::ChosenSource chosen = sources::choose_source(lammps_kinds, *vm);
    sources::SourceArguments other = chosen.given;
    other.erase("timestep");
    if (vm->count("other-timestep")) other["timestep"] = (*vm)["other-timestep"].as<std::string>();
    if (vm->count("other-lammps-atoms") != vm->count("other-lammps-pairs"))
      throw po::error("--other-lammps-atoms and --other-lammps-pairs go together");
    if (vm->count("other-lammps-atoms")) {
      other["lammps-atoms"] = (*vm)["other-lammps-atoms"].as<std::string>();
      other["lammps-pairs"] = (*vm)["other-lammps-pairs"].as<std::string>();
    } else if (!vm->count("other-timestep")) {
      throw po::error("frame B: --other-timestep, or --other-lammps-atoms and --other-lammps-pairs");
    }
    a = sources::next_frame(*chosen.open()).frame;
    b = sources::next_frame(*chosen.kind->open(other)).frame;
  } else {
    a = read(files[0], particles_a);
    b = read(files[1], particles_b);
  }
  // Frame A is frame 0 of run "a", frame B frame 0 of run "b".
  query::LoadedFrames frames;
  frames.add("a", 0, std::move(a));
  frames.add("b", 0, std::move(b));
  const query::PairAnswer answer =
      query::pair_query(frames, {"a", 0, "b", 0, {choice, d, kind, convention}, 0, static_cast<std::size_t>(k)});
  nlohmann::json out = to_json(answer.distance);
  out["explain"] = explain_terms_json(*answer.explained);
  out["metric"] = choice.name;
  if (choice.q) out["q"] = *choice.q;
  out["dim"] = d;
  out["force"] = std::string(to_string(kind));
  out["essential"] = std::string(to_string(convention));
  out["k"] = k;
  out["seconds"] = answer.seconds;
  if (format == "json")
    std::cout << out.dump() << "\n";
  else
    write_explain_table(std::cout, out, choice.label());
  return 0;
}

}  // namespace fnet::analyze
