#include "server/fnet-simd/output_sinks.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/build_info/build_info.hpp"
#include "common/codec/run_info_json.hpp"

namespace fnet::sim {

RunInfo run_info(const Params& p, const std::string& run_id, const std::string& ensemble) {
  // Designated, so that the compiler checks the order; a field left out fails sim.OutputSinks.
  return {.run_id = run_id,
          .particles = static_cast<std::uint32_t>(p.particles),
          .polydispersity = p.polydispersity,
          .friction = p.mu,
          .k_n = p.kn,
          .restitution = p.en,
          .kt_over_kn = p.kt_ratio,
          .compression_speed = p.compression_speed,
          .dt = derive(p).dt,
          .final_density = p.rho_final,
          .frames = static_cast<std::uint32_t>(p.frames),
          .seed = p.seed,
          .config_json = to_json(p).dump(),
          .ensemble = ensemble};
}

void write_csv_provenance(const std::filesystem::path& dir, const RunInfo& info) {
  const BuildInfo b = build_info();
  const nlohmann::json doc = {
      {"fnet_version", b.version}, {"fnet_commit", b.commit}, {"created", utc_timestamp()}, {"run", to_json(info)}};
  const std::filesystem::path path = dir / "provenance.json";
  std::ofstream out(path, std::ios::trunc);
  out << doc.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

RunFrame run_frame(const FrameSnapshot& s) {
  RunFrame f;
  f.header = {s.run_id, static_cast<std::uint32_t>(s.index), static_cast<std::uint64_t>(s.step), s.time, s.rho, s.z};
  f.frame = s.frame;
  f.frame.label = frame_label(s.run_id, f.header.index);
  f.wall_contacts.reserve(s.wall_contacts.size());
  for (const WallContact& w : s.wall_contacts)
    f.wall_contacts.push_back({static_cast<std::uint32_t>(w.grain), w.fn, w.ft});
  return f;
}

DdsSink::DdsSink(dds_domainid_t domain, const RunInfo& info) : publisher_(domain), run_id_(info.run_id) {
  publisher_.publish(info);
}

void DdsSink::operator()(const RunFrame& frame) {
  publisher_.publish(frame);
  through_ = std::max(through_, frame.header.index + 1);
  reached_ = reached_ || subscriber_now();
}

Delivery DdsSink::finish(double ack_timeout_seconds, double linger_seconds, const std::function<bool()>& should_stop) {
  Delivery delivery;
  const auto started = std::chrono::steady_clock::now();
  delivery.acknowledged = publisher_.wait_for_acks(static_cast<dds_duration_t>(ack_timeout_seconds * 1e9));
  delivery.lost_readers = publisher_.lost_frame_readers();  // before lingering: one may leave then
  const double left =
      ack_timeout_seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  delivery.stores = dds::wait_for_stores([this] { return publisher_.servers_storing(run_id_); }, run_id_, through_,
                                         std::max(0.0, left));
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(linger_seconds);
  while (std::chrono::steady_clock::now() < until && !should_stop()) {
    reached_ = reached_ || subscriber_now();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  reached_ = reached_ || subscriber_now();
  return delivery;
}

RunFileSink::RunFileSink(const std::filesystem::path& path, const RunInfo& info, bool resume, std::size_t first_frame)
    : writer_(resume && std::filesystem::exists(path) ? std::make_unique<RunFileWriter>(RunFileWriter::reopen(
                                                            path, static_cast<std::uint32_t>(first_frame)))
                                                      : std::make_unique<RunFileWriter>(path, info)) {}

void RunFileSink::operator()(const RunFrame& frame) { writer_->append(frame); }

}  // namespace fnet::sim
