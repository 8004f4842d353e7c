// A ForceFrame sample as fnet-server receives it from DDS, its fields taken from the bytes, through
// the checks the server applies before it stores anything: the sample decoded, the run id checked,
// the frame validated, and its diagrams computed (what the server does with a frame it accepts).
// Input: the fields in the IDL's order (proto/fnet.idl), then the sequences' lengths and values.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/analysis/frame_analysis.hpp"
#include "common/run/run_names.hpp"
#include "common/transport/frame_sample.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

// A sequence borrowing its buffer from `values`, as DDS lends a sample's.
template <class Seq, class T>
Seq lent(std::vector<T>& values) {
  Seq seq{};
  seq._maximum = seq._length = static_cast<std::uint32_t>(values.size());
  seq._buffer = values.data();
  return seq;
}

template <class T, class Take>
std::vector<T> values(fnet::fuzz::ByteReader& in, std::size_t max_count, Take take) {
  std::vector<T> out(in.take_count(max_count));
  for (T& v : out) v = take();
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  fuzz::ByteReader in(data, size);
  fnet_ForceFrame s{};
  const std::string run_id = in.take_string(sizeof s.run_id - 1);  // DDS ends a bounded string with a NUL
  std::copy(run_id.begin(), run_id.end(), s.run_id);
  s.frame = in.take<std::uint32_t>();
  s.step = in.take<std::uint64_t>();
  s.time = in.take<double>();
  s.rho = in.take<double>();
  s.z = in.take<double>();
  s.particle_count = in.take<std::uint32_t>();
  s.dimension = in.take<std::uint8_t>();
  // Indices mostly small, so that frames get as far as their diagrams.
  const auto index = [&] { return static_cast<std::uint32_t>(in.take<std::uint16_t>()); };
  const auto real = [&] { return in.take<double>(); };
  std::vector<double> particles = values<double>(in, 3 * 64, real);
  std::vector<double> particle_z = values<double>(in, 64, real);
  std::vector<std::uint32_t> pairs = values<std::uint32_t>(in, 2 * 128, index);
  std::vector<double> forces = values<double>(in, 2 * 128, real);
  std::vector<std::uint32_t> wall_particles = values<std::uint32_t>(in, 32, index);
  std::vector<double> wall_forces = values<double>(in, 2 * 32, real);
  s.particles = lent<dds_sequence_double>(particles);
  s.particle_z = lent<dds_sequence_double>(particle_z);
  s.contact_pairs = lent<dds_sequence_uint32>(pairs);
  s.contact_forces = lent<dds_sequence_double>(forces);
  s.wall_contact_particles = lent<dds_sequence_uint32>(wall_particles);
  s.wall_contact_forces = lent<dds_sequence_double>(wall_forces);

  const std::string label = fnet::frame_label(s.run_id, s.frame);
  try {
    const fnet::RunFrame frame = fnet::dds::decode_frame_sample(s);
    if (!fnet::run_id_problem(frame.header.run_id).empty()) return 0;  // the registry refuses it by name
    fnet::validate(frame.frame);
    fnet::analyze_frame(frame.frame);
  } catch (const fnet::FrameError& e) {
    fuzz::require_names(e, {label});
  }
  return 0;
}
