// A LAMMPS log as fnet-analyze reads it: the dimension its input echoes (--lammps-log) and a column
// of its thermo output by step (--rho log:LOG:COLUMN). Input: the column's name [@@@@ the log].
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "server/sources/lammps_dimension.hpp"
#include "server/sources/lammps_thermo.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto files = fuzz::input_files(data, size);
  std::string column(files[0].substr(0, files[0].find('\n')));
  const auto log = fuzz::write_file("log.lammps", files.size() > 1 ? files[1] : "");
  try {
    fnet::sources::logged_dimension(log);
  } catch (const std::runtime_error& e) {
    fuzz::require_names(e, {log.string()});
  }
  try {
    fnet::sources::thermo_column(log, column);
  } catch (const std::runtime_error& e) {
    fuzz::require_names(e, {log.string()});
  }
  return 0;
}
