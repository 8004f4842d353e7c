// A frame as it travels from the simulation to the analysis: the force network plus where it sits
// in its run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/run/member_count.hpp"
#include "common/topology/frame.hpp"

namespace fnet {

struct WallContact {
  std::uint32_t particle = 0;
  double fn = 0, ft = 0;  // signed normal force, tangential magnitude
  bool operator==(const WallContact&) const = default;
};

struct FrameHeader {
  std::string run_id;
  std::uint32_t index = 0;  // 0-based within the run
  std::uint64_t step = 0;
  double time = 0;
  double rho = 0;  // packing fraction
  double z = 0;    // 2 x grain-grain contacts with F_n > 0 / N
  bool operator==(const FrameHeader&) const = default;
};

struct RunFrame {
  FrameHeader header;
  Frame frame;  // frame.label names run and index
  std::vector<WallContact> wall_contacts;
};

// The parameters of a run as the simulation announces them; config_json holds every parameter.
// What each field means, and what every codec calls it: for_each_run_info_field below.
struct RunInfo {
  std::string run_id;
  std::uint32_t particles = 0;
  double polydispersity = 0, friction = 0, k_n = 0, restitution = 0, kt_over_kn = 0;
  double compression_speed = 0, dt = 0, final_density = 0;
  std::uint32_t frames = 0;
  std::uint64_t seed = 0;
  std::string config_json;
  std::string ensemble;  // the realizations' setting this run belongs to; empty: none
  bool operator==(const RunInfo&) const = default;
};

// One field of RunInfo as the codecs name it.
struct RunInfoField {
  const char* name;       // the member, in RunInfo and in the IDL's fnet_RunInfo (proto/fnet.idl)
  const char* attribute;  // HDF5 attribute of the run file's root (proto/run_file.md)
  const char* key;        // JSON key (proto/api.md, and the analysis store's announcements)
  const char* meaning;
  // The value is JSON text: JSON carries it parsed under `key` (or verbatim under `name`).
  bool json_text = false;
  // Added in version 2 of the announcement: run files and stores written before lack it, and
  // readers take it as empty.
  bool since_v2 = false;
};

// The one list of RunInfo's fields, which every codec walks (DDS both ways, the run file, JSON):
// calls f(field, records.member...) for each field. Generic in the records because the DDS codec
// walks the generated C struct, whose members have RunInfo's names, alongside a RunInfo: a field
// the IDL lacks does not compile, and one only the IDL has fails a transport test. The order is
// the order in which run files have always had their attributes written, so that files stay the
// same byte for byte.
template <class F, class... Records>
constexpr void for_each_run_info_field(F&& f, Records&... r) {
  f(RunInfoField{"run_id", "run_id", "run", "the run's id (the DDS key)"}, r.run_id...);
  f(RunInfoField{"config_json", "config_json", "config", "every parameter of the run, as the daemon read it", true},
    r.config_json...);
  f(RunInfoField{"particles", "particles", "particles", "N grains (walls excluded)"}, r.particles...);
  f(RunInfoField{"polydispersity", "polydispersity", "polydispersity",
                 "r_p: diameters uniform in [1 - r_p/2, 1 + r_p/2]"},
    r.polydispersity...);
  f(RunInfoField{"friction", "friction", "friction", "mu_s, Coulomb coefficient"}, r.friction...);
  f(RunInfoField{"k_n", "k_n", "k_n", "normal stiffness, m g / d"}, r.k_n...);
  f(RunInfoField{"restitution", "restitution", "restitution", "e_n, normal restitution"}, r.restitution...);
  f(RunInfoField{"kt_over_kn", "kt_over_kn", "kt_over_kn", "k_t / k_n"}, r.kt_over_kn...);
  f(RunInfoField{"compression_speed", "compression_speed", "compression_speed", "v_c, d_ave / tau_c, each wall"},
    r.compression_speed...);
  f(RunInfoField{"dt", "dt", "dt", "integration step, in the engine's time unit sqrt(d / g)"}, r.dt...);
  f(RunInfoField{"final_density", "final_density", "final_density", "rho at which the compression stops"},
    r.final_density...);
  f(RunInfoField{"frames", "frames_planned", "frames", "frames planned over the compression"}, r.frames...);
  f(RunInfoField{"seed", "seed", "seed", "random seed"}, r.seed...);
  f(RunInfoField{"ensemble", "ensemble", "ensemble",
                 "the ensemble of realizations (one setting, several seeds) the run belongs to; empty: none", false,
                 true},
    r.ensemble...);
}

consteval std::size_t run_info_field_count() {
  std::size_t n = 0;
  for_each_run_info_field([&n](const RunInfoField&) { ++n; });
  return n;
}
static_assert(run_info_field_count() == member_count<RunInfo>(),
              "for_each_run_info_field must list every member of RunInfo, once");

// "run R frame K": how every message about a frame names it.
std::string frame_label(const std::string& run_id, std::uint32_t index);

}  // namespace fnet
