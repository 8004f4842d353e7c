// fnet-simd --config FILE: the parameters a config file sets, checked as fnet-simd checks them;
// what --show-params prints of them loads back to the same parameters. Input: the config file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "server/dem/params.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const auto path = fuzz::write_file("config.json", {reinterpret_cast<const char*>(data), size});
  try {
    fnet::sim::Params p;
    fnet::sim::apply_config_file(p, path);
    fnet::sim::validate(p);
    fnet::sim::derive(p);
    fnet::sim::Params again;
    fnet::sim::apply_json(again, fnet::sim::to_json(p));
    if (fnet::sim::to_json(again) != fnet::sim::to_json(p)) {
      std::cerr << "fuzz: --show-params does not load back: " << fnet::sim::to_json(p).dump() << "\n";
      std::abort();
    }
  } catch (const std::invalid_argument& e) {
    fuzz::require_names(e, {path.string(), "invalid parameter"});
  }
  return 0;
}
