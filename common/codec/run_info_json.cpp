#include "common/codec/run_info_json.hpp"

namespace fnet {

nlohmann::json to_json(const RunInfo& i) {
  nlohmann::json config = nlohmann::json::parse(i.config_json, nullptr, false);
  return {{"run", i.run_id},
          {"particles", i.particles},
          {"polydispersity", i.polydispersity},
          {"friction", i.friction},
          {"k_n", i.k_n},
          {"restitution", i.restitution},
          {"kt_over_kn", i.kt_over_kn},
          {"compression_speed", i.compression_speed},
          {"dt", i.dt},
          {"final_density", i.final_density},
          {"frames", i.frames},
          {"seed", i.seed},
          {"config", config.is_discarded() ? nlohmann::json(i.config_json) : config}};
}

RunInfo run_info_from_json(const nlohmann::json& v) {
  RunInfo i;
  i.run_id = v.at("run").get<std::string>();
  i.particles = v.at("particles").get<std::uint32_t>();
  i.polydispersity = v.at("polydispersity").get<double>();
  i.friction = v.at("friction").get<double>();
  i.k_n = v.at("k_n").get<double>();
  i.restitution = v.at("restitution").get<double>();
  i.kt_over_kn = v.at("kt_over_kn").get<double>();
  i.compression_speed = v.at("compression_speed").get<double>();
  i.dt = v.at("dt").get<double>();
  i.final_density = v.at("final_density").get<double>();
  i.frames = v.at("frames").get<std::uint32_t>();
  i.seed = v.at("seed").get<std::uint64_t>();
  if (v.contains("config_json")) {  // the verbatim text, as the store keeps it
    i.config_json = v.at("config_json").get<std::string>();
  } else {
    const nlohmann::json& config = v.at("config");
    i.config_json = config.is_string() ? config.get<std::string>() : config.dump();
  }
  return i;
}

}  // namespace fnet
