// One persistence diagram of a committed frame, with the size of the complex it was computed on
// (diagram.get).
#pragma once

#include <cstdint>
#include <string>

#include "common/run/run_frame.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

struct DiagramRequest {
  std::string run;
  std::uint32_t frame = 0;
  int dim = 0;  // 0 or 1
  ForceKind force = ForceKind::normal;
};

struct DiagramAnswer {
  FrameHeader header;
  std::size_t vertices = 0, edges = 0, triangles = 0;  // of the force network's flag complex
  Diagram points;                                      // PD`dim`
};

// UnknownFrame when the frame is not committed.
DiagramAnswer diagram_query(const FrameLookup& frames, const DiagramRequest& request);

}  // namespace fnet::query
