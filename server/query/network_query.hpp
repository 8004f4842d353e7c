// The force network of a committed frame as its run's store keeps it: its grains and contacts,
// the mean force of each kind (the unit of every normalized force) and its domain (network.get).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/analysis/blocks.hpp"
#include "common/run/run_frame.hpp"
#include "common/topology/frame.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

struct NetworkRequest {
  std::string run;
  std::uint32_t frame = 0;
};

struct NetworkAnswer {
  FrameHeader header;
  Frame network;
  double mean_normal = 0, mean_tangential = 0;  // over the contacts whose force of that kind is > 0
  std::optional<BlockDomain> domain;            // the grains' bounding box (blocks.hpp); none without positions
};

// UnknownFrame when the frame is not committed; NoNetwork when its network is not stored.
NetworkAnswer network_query(const FrameLookup& frames, const NetworkRequest& request);

}  // namespace fnet::query
