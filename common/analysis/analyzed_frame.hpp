// What the analysis of a run settles for each of its frames: accepted with its diagrams and its
// distances to the previous accepted frame, or rejected with a reason.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "common/analysis/frame_analysis.hpp"
#include "common/run/run_frame.hpp"

namespace fnet {

struct AnalyzedFrame {
  FrameHeader header;
  int dimension = 2;  // the frame's: 2 (disks) or 3 (spheres)
  FrameDiagramSet diagrams;
  std::optional<std::uint32_t> previous;  // the accepted frame the distances are measured from
  StepDistances distances;                // meaningful only with a previous frame
  // The force network as received, for the store to keep; null in the frames fnet-server keeps in
  // memory (it reads networks back from the store) and in frames read back from a store.
  std::shared_ptr<const Frame> network;
};

struct RejectedFrame {
  std::uint32_t index = 0;
  std::string reason;
  bool operator==(const RejectedFrame&) const = default;
};

}  // namespace fnet
