// Frames and run announcements over Cyclone DDS: topics "fnet_RunInfo" and "fnet_ForceFrame",
// both keyed by run_id, with the QoS that loses nothing (reliable, keep-all, transient-local with
// a keep-all durability service so that a reader joining after the run still gets every frame).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <dds/dds.h>

#include "common/run/run_frame.hpp"
#include "common/transport/dds_entity.hpp"
#include "common/transport/run_status_topic.hpp"

namespace fnet::dds {

inline constexpr const char* kRunInfoTopic = "fnet_RunInfo";
inline constexpr const char* kFrameTopic = "fnet_ForceFrame";

class FramePublisher {
 public:
  // max_blocking: how long one write may wait for a slow reader's resource limits before it is
  // retried (a timed-out write is not queued by DDS).
  explicit FramePublisher(dds_domainid_t domain = DDS_DOMAIN_DEFAULT, dds_duration_t max_blocking = DDS_SECS(1));

  void publish(const RunInfo& info);
  // Retries a write that timed out until `give_up` has passed; throws dds::Error then.
  void publish(const RunFrame& frame, dds_duration_t give_up = DDS_SECS(600));

  // Subscribers matched on both topics: a frame written once this is positive reaches one whose
  // announcement reader is matched too (the two topics are discovered separately).
  std::uint32_t matched_readers() const;
  // Frame readers matched at some point that are no longer: gone, or silent for longer than the
  // DDS lease (10 s by default). A writer does not wait for them: what they had not acknowledged
  // is theirs again only if they come back while this publisher still lives.
  std::uint32_t lost_frame_readers() const;
  // Blocks until every matched reader acknowledged everything written, or timeout; true if all did.
  bool wait_for_acks(dds_duration_t timeout) const;
  // The fnet-servers among the matched frame readers, each with its latest status of `run_id`'s
  // store (run_status_topic.hpp).
  std::vector<ServerStore> servers_storing(const std::string& run_id);

 private:
  Entity participant_;
  dds_entity_t info_writer_ = 0, frame_writer_ = 0;
  RunStatusReader status_;
};

// A frame taken from DDS but not decoded: its header, and why (it names the run, the frame and
// the bound).
struct RefusedFrame {
  FrameHeader header;
  std::string reason;
};

struct Received {
  std::vector<RunInfo> infos;
  std::vector<RunFrame> frames;
  std::vector<RefusedFrame> refused;
  std::vector<std::string> malformed;  // samples that could not be decoded, with the reason
};

// The largest frame a subscriber decodes (frame_bytes of its grains, contacts and wall contacts);
// `name` says where the bound is set, in the reason of a refusal.
struct FrameSizeBound {
  std::size_t max_bytes = SIZE_MAX;
  std::string name = "the frame size bound";
};

class FrameSubscriber {
 public:
  // max_frames_buffered: DDS resource limit on frames held by this reader before the writer waits
  // (DDS_LENGTH_UNLIMITED for none).
  explicit FrameSubscriber(dds_domainid_t domain = DDS_DOMAIN_DEFAULT,
                           std::int32_t max_frames_buffered = DDS_LENGTH_UNLIMITED, FrameSizeBound bound = {});

  // Waits up to `timeout` for data, then takes everything available, frames one at a time until
  // max_frames are taken or the frames taken hold max_bytes (frame_bytes): the frame that reaches
  // it is the last. A frame larger than the bound is refused unread (Received::refused).
  Received take(dds_duration_t timeout, std::size_t max_frames = SIZE_MAX, std::size_t max_bytes = SIZE_MAX);
  // Tells the publishers of status.run_id how far the run is in this reader's store (thread-safe).
  void publish(const RunStatus& status);

 private:
  Entity participant_;
  dds_entity_t info_reader_ = 0, frame_reader_ = 0, waitset_ = 0;
  std::optional<RunStatusWriter> status_;  // made after the participant
  FrameSizeBound bound_;
};

}  // namespace fnet::dds
