// A LAMMPS run as fnet-analyze store --lammps-atoms A --lammps-pairs P reads it (proto/lammps.md):
// the per-atom and pair dumps, and the log when a flag names it, every frame made and checked.
// Input: the flags [@@@@ atoms dump [@@@@ pairs dump [@@@@ log]]]. The flags are lines FLAG=VALUE
// of the kind's optional flags (wall-types, columns, check-balance, rho, dimension, lammps-log);
// "rho=log:COLUMN" and "lammps-log=" name the input's log.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include <boost/program_options/errors.hpp>

#include "server/sources/source_kinds.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

fnet::sources::SourceArguments flags_of(std::string_view text, const std::string& log) {
  fnet::sources::SourceArguments given;
  while (!text.empty()) {
    const std::string_view line = text.substr(0, text.find('\n'));
    text.remove_prefix(std::min(text.size(), line.size() + 1));
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) continue;
    const std::string flag(line.substr(0, eq));
    std::string value(line.substr(eq + 1));
    if (flag == "rho" && value.rfind("log:", 0) == 0) value = "log:" + log + ":" + value.substr(4);
    if (flag == "lammps-log") value = log;
    if (flag == "wall-types" || flag == "columns" || flag == "check-balance" || flag == "rho" || flag == "dimension" ||
        flag == "lammps-log")
      given[flag] = value;
  }
  return given;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto files = fuzz::input_files(data, size);
  fuzz::clear_scratch();
  const std::string atoms = fuzz::write_file("atoms.txt", files.size() > 1 ? files[1] : "").string();
  const std::string pairs = fuzz::write_file("pairs.txt", files.size() > 2 ? files[2] : "").string();
  const std::string log = fuzz::write_file("log.lammps", files.size() > 3 ? files[3] : "").string();
  fnet::sources::SourceArguments given = flags_of(files[0], log);
  given["lammps-atoms"] = atoms;
  given["lammps-pairs"] = pairs;
  try {
    const auto source = fnet::sources::lammps_kind().open(given);
    while (const auto frame = source->next()) fnet::validate(frame->frame);
  } catch (const boost::program_options::error& e) {
    fuzz::require_names(e, {"--"});
  } catch (const fnet::FrameError& e) {
    fuzz::require_names(e, {"frame "});
  } catch (const std::runtime_error& e) {
    fuzz::require_names(e, {atoms, pairs, log});
  }
  return 0;
}
