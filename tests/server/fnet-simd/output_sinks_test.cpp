// The run announcement fnet-simd makes from its parameters.
#include "server/fnet-simd/output_sinks.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_info_sample.hpp"

namespace fnet::sim {
namespace {

TEST(OutputSinks, RunInfoCarriesEveryParameterItAnnounces) {
  Params p;  // every announced parameter away from its default, no two alike
  p.particles = 321;
  p.polydispersity = 0.31;
  p.mu = 0.42;
  p.kn = 3210;
  p.en = 0.63;
  p.kt_ratio = 0.74;
  p.compression_speed = 5.5e-4;
  p.dt_divisor = 64;
  p.rho_final = 0.86;
  p.frames = 17;
  p.seed = 987654321987ull;
  const RunInfo info = run_info(p, "sinks", "mu042");

  const RunInfo defaults;
  for_each_run_info_field([](const RunInfoField& field, const auto& value,
                             const auto& default_value) { EXPECT_NE(value, default_value) << field.name; },
                          info, defaults);
  testing::expect_same_fields({.run_id = "sinks",
                               .particles = 321,
                               .polydispersity = 0.31,
                               .friction = 0.42,
                               .k_n = 3210,
                               .restitution = 0.63,
                               .kt_over_kn = 0.74,
                               .compression_speed = 5.5e-4,
                               .dt = derive(p).dt,
                               .final_density = 0.86,
                               .frames = 17,
                               .seed = 987654321987ull,
                               .config_json = to_json(p).dump(),
                               .ensemble = "mu042"},
                              info);
  EXPECT_EQ(nlohmann::json::parse(info.config_json).at("mu"), 0.42);
}

}  // namespace
}  // namespace fnet::sim
