#include "common/transport/frame_transport.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include "common/run/frame_bounds.hpp"
#include "common/run/particle_columns.hpp"
#include "common/transport/frame_sample.hpp"
#include "fnet.h"

namespace fnet::dds {
namespace {

void set_bounded(char* dst, std::size_t capacity, const std::string& value, const char* field) {
  if (value.size() > capacity)
    throw std::invalid_argument(std::string(field) + " longer than " + std::to_string(capacity) + " bytes");
  std::memcpy(dst, value.data(), value.size());
  dst[value.size()] = '\0';
}

void set_qos(Qos& qos, bool writer, std::int32_t max_samples) {
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  if (writer) {
    // Late readers are served from the durability service's history, not the writer's.
    dds_qset_durability_service(qos.get(), 0, DDS_HISTORY_KEEP_ALL, 0, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                                DDS_LENGTH_UNLIMITED);
  } else {
    dds_qset_resource_limits(qos.get(), max_samples, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  }
}

template <class Seq, class T>
Seq borrow(std::vector<T>& values) {
  Seq seq{};
  seq._maximum = seq._length = static_cast<std::uint32_t>(values.size());
  seq._buffer = values.data();
  seq._release = false;  // dds_write copies; the vector keeps ownership
  return seq;
}

RunFrame decode(const fnet_ForceFrame& s) { return decode_frame_sample(s); }

// RunInfo <-> fnet_RunInfo, one field at a time: bounded strings are char arrays in the C struct, every
// other field has the same type on both sides (no overload, no compilation, if the IDL's type differs).
template <std::size_t N>
void to_wire(const RunInfoField& field, const std::string& value, char (&wire)[N]) {
  set_bounded(wire, N - 1, value, field.name);
}
template <class T>
void to_wire(const RunInfoField&, const T& value, T& wire) {
  wire = value;
}
template <std::size_t N>
void from_wire(std::string& value, const char (&wire)[N]) {
  value = wire;
}
template <class T>
void from_wire(T& value, const T& wire) {
  value = wire;
}

RunInfo decode(const fnet_RunInfo& s) {
  RunInfo info;
  for_each_run_info_field([](const RunInfoField&, auto& value, const auto& wire) { from_wire(value, wire); }, info, s);
  return info;
}

// Takes what is available from `reader` as loans, `batch` samples at a time, handing each valid
// sample to `sink` until it returns false.
template <class Sample, class Sink>
void take_all(dds_entity_t reader, std::size_t batch, Sink sink) {
  constexpr std::size_t kBatch = 64;
  void* samples[kBatch];
  dds_sample_info_t infos[kBatch];
  const std::size_t want = std::clamp<std::size_t>(batch, 1, kBatch);
  bool more = true;
  while (more) {
    samples[0] = nullptr;
    const dds_return_t n = dds_take(reader, samples, infos, want, static_cast<std::uint32_t>(want));
    if (n < 0) throw Error("dds_take", n);
    if (n == 0) return;
    for (dds_return_t k = 0; k < n; ++k)
      if (infos[k].valid_data) more = sink(*static_cast<const Sample*>(samples[k])) && more;
    dds_return_loan(reader, samples, n);
  }
}

// The bytes a frame sample holds once decoded (frame_bytes), from its sequences' lengths alone.
std::size_t sample_bytes(const fnet_ForceFrame& s) {
  return frame_bytes(s.particle_count, s.contact_pairs._length / 2, s.wall_contact_particles._length);
}

// The two topics, created alike by the publisher and the subscriber.
struct Topics {
  dds_entity_t info, frame;
};
Topics create_topics(dds_entity_t participant) {
  return {check(dds_create_topic(participant, &fnet_RunInfo_desc, kRunInfoTopic, nullptr, nullptr),
                "dds_create_topic(RunInfo)"),
          check(dds_create_topic(participant, &fnet_ForceFrame_desc, kFrameTopic, nullptr, nullptr),
                "dds_create_topic(ForceFrame)")};
}

}  // namespace

FramePublisher::FramePublisher(dds_domainid_t domain, dds_duration_t max_blocking)
    : participant_(check(dds_create_participant(domain, nullptr, nullptr), "dds_create_participant")),
      status_(participant_.get()) {
  const auto [info_topic, frame_topic] = create_topics(participant_.get());
  Qos qos;
  set_qos(qos, true, DDS_LENGTH_UNLIMITED);
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, max_blocking);
  info_writer_ =
      check(dds_create_writer(participant_.get(), info_topic, qos.get(), nullptr), "dds_create_writer(RunInfo)");
  frame_writer_ =
      check(dds_create_writer(participant_.get(), frame_topic, qos.get(), nullptr), "dds_create_writer(ForceFrame)");
}

std::vector<ServerStore> FramePublisher::servers_storing(const std::string& run_id) {
  return status_.servers(frame_writer_, run_id);
}

void FramePublisher::publish(const RunInfo& info) {
  fnet_RunInfo s{};
  for_each_run_info_field([](const RunInfoField& field, const auto& value, auto& wire) { to_wire(field, value, wire); },
                          info, s);
  const dds_return_t rc = dds_write(info_writer_, &s);
  if (rc != DDS_RETCODE_OK) throw Error("dds_write(RunInfo)", rc);
}

void FramePublisher::publish(const RunFrame& frame, dds_duration_t give_up) {
  const Frame& f = frame.frame;
  ParticleColumns particles = particle_columns(f, false);  // a 2D frame's z is 0: not sent
  std::vector<std::uint32_t> pairs(2 * f.contacts.size());
  std::vector<double> forces(2 * f.contacts.size());
  for (std::size_t k = 0; k < f.contacts.size(); ++k) {
    pairs[2 * k] = static_cast<std::uint32_t>(f.contacts[k].i);
    pairs[2 * k + 1] = static_cast<std::uint32_t>(f.contacts[k].j);
    forces[2 * k] = f.contacts[k].fn;
    forces[2 * k + 1] = f.contacts[k].ft;
  }
  std::vector<std::uint32_t> wall_particles(frame.wall_contacts.size());
  std::vector<double> wall_forces(2 * frame.wall_contacts.size());
  for (std::size_t k = 0; k < frame.wall_contacts.size(); ++k) {
    wall_particles[k] = frame.wall_contacts[k].particle;
    wall_forces[2 * k] = frame.wall_contacts[k].fn;
    wall_forces[2 * k + 1] = frame.wall_contacts[k].ft;
  }
  fnet_ForceFrame s{};
  set_bounded(s.run_id, sizeof s.run_id - 1, frame.header.run_id, "run_id");
  s.frame = frame.header.index;
  s.step = frame.header.step;
  s.time = frame.header.time;
  s.rho = frame.header.rho;
  s.z = frame.header.z;
  s.particle_count = static_cast<std::uint32_t>(f.particle_count);
  s.particles = borrow<dds_sequence_double>(particles.xyr);
  s.contact_pairs = borrow<dds_sequence_uint32>(pairs);
  s.contact_forces = borrow<dds_sequence_double>(forces);
  s.wall_contact_particles = borrow<dds_sequence_uint32>(wall_particles);
  s.wall_contact_forces = borrow<dds_sequence_double>(wall_forces);
  s.dimension = static_cast<std::uint8_t>(f.dimension);
  s.particle_z = borrow<dds_sequence_double>(particles.z);

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(give_up);
  while (true) {
    const dds_return_t rc = dds_write(frame_writer_, &s);
    if (rc == DDS_RETCODE_OK) return;
    // A write that timed out on a full reader is not queued: retry until the reader drains.
    if (rc != DDS_RETCODE_TIMEOUT || std::chrono::steady_clock::now() > deadline)
      throw Error("dds_write(ForceFrame) " + frame_label(frame.header.run_id, frame.header.index), rc);
  }
}

namespace {

// Readers a writer is matched with now, read from the writer's own match set: the one
// dds_wait_for_acks waits on. The matched status's current_count trails it: DDS updates the status
// after it has dropped a reader and woken the writer's waiters.
std::uint32_t matched_now(dds_entity_t writer) {
  const dds_return_t n = dds_get_matched_subscriptions(writer, nullptr, 0);
  if (n < 0) throw Error("dds_get_matched_subscriptions", n);
  return static_cast<std::uint32_t>(n);
}

}  // namespace

std::uint32_t FramePublisher::matched_readers() const {
  return std::min(matched_now(info_writer_), matched_now(frame_writer_));
}

std::uint32_t FramePublisher::lost_frame_readers() const {
  dds_publication_matched_status_t status{};
  check(dds_get_publication_matched_status(frame_writer_, &status), "dds_get_publication_matched_status");
  const std::uint32_t now = matched_now(frame_writer_);
  return status.total_count > now ? status.total_count - now : 0;  // a new match may not be counted yet
}

bool FramePublisher::wait_for_acks(dds_duration_t timeout) const {
  const dds_return_t a = dds_wait_for_acks(info_writer_, timeout);
  const dds_return_t b = dds_wait_for_acks(frame_writer_, timeout);
  return a == DDS_RETCODE_OK && b == DDS_RETCODE_OK;
}

FrameSubscriber::FrameSubscriber(dds_domainid_t domain, std::int32_t max_frames_buffered, FrameSizeBound bound)
    : participant_(check(dds_create_participant(domain, nullptr, nullptr), "dds_create_participant")),
      bound_(std::move(bound)) {
  const auto [info_topic, frame_topic] = create_topics(participant_.get());
  Qos info_qos, frame_qos;
  set_qos(info_qos, false, DDS_LENGTH_UNLIMITED);
  set_qos(frame_qos, false, max_frames_buffered);
  info_reader_ =
      check(dds_create_reader(participant_.get(), info_topic, info_qos.get(), nullptr), "dds_create_reader(RunInfo)");
  frame_reader_ = check(dds_create_reader(participant_.get(), frame_topic, frame_qos.get(), nullptr),
                        "dds_create_reader(ForceFrame)");
  waitset_ = check(dds_create_waitset(participant_.get()), "dds_create_waitset");
  status_.emplace(participant_.get());
  for (const dds_entity_t reader : {info_reader_, frame_reader_}) {
    const dds_entity_t cond = check(dds_create_readcondition(reader, DDS_ANY_STATE), "dds_create_readcondition");
    const dds_return_t rc = dds_waitset_attach(waitset_, cond, reader);
    if (rc != DDS_RETCODE_OK) throw Error("dds_waitset_attach", rc);
  }
}

void FrameSubscriber::publish(const RunStatus& status) { status_->write(status); }

Received FrameSubscriber::take(dds_duration_t timeout, std::size_t max_frames, std::size_t max_bytes) {
  const dds_return_t rc = dds_waitset_wait(waitset_, nullptr, 0, timeout);
  if (rc < 0) throw Error("dds_waitset_wait", rc);
  Received out;
  // Announcements first; a frame may still precede its run's announcement (separate topics).
  take_all<fnet_RunInfo>(info_reader_, SIZE_MAX, [&](const fnet_RunInfo& s) {
    out.infos.push_back(decode(s));
    return true;
  });
  if (max_frames == 0 || max_bytes == 0) return out;
  // One frame at a time, so that none is taken beyond the budgets.
  std::size_t frames = 0, bytes = 0;
  take_all<fnet_ForceFrame>(frame_reader_, 1, [&](const fnet_ForceFrame& s) {
    const std::size_t size = sample_bytes(s);
    if (size > bound_.max_bytes) {
      out.refused.push_back({{s.run_id, s.frame, s.step, s.time, s.rho, s.z},
                             frame_label(s.run_id, s.frame) + ": refused unread: its " +
                                 std::to_string(s.particle_count) + " grains and " +
                                 std::to_string(s.contact_pairs._length / 2) + " contacts hold " + mebibytes(size) +
                                 ", above " + bound_.name + ", " + mebibytes(bound_.max_bytes)});
      return true;
    }
    try {
      out.frames.push_back(decode(s));
    } catch (const FrameError& e) {
      out.malformed.emplace_back(e.what());
    }
    bytes += size;
    return ++frames < max_frames && bytes < max_bytes;
  });
  return out;
}

}  // namespace fnet::dds
