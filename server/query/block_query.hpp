// Where a run's force network changed between two frames, cell by cell over a k x k grid, or
// k x k x k for 3D frames (common/analysis/blocks.hpp; blocks.get).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/analysis/blocks.hpp"
#include "common/analysis/step_series.hpp"
#include "server/query/frame_lookup.hpp"

namespace fnet::query {

struct BlockRequest {
  std::string run;
  std::uint32_t frame = 0, other_frame = 0;
  int k = 2;  // kMinBlocks..kMaxBlocks
  StepQuery measure;
};

struct BlockAnswer {
  std::vector<BlockCell> cells, other_cells;  // the same grid over each frame, in cell order (blocks.hpp)
  std::vector<BlockDistance> distances;       // cell by cell, in cell order
  std::size_t largest = 0;                    // the first cell of the largest distance (+inf the largest)
  double seconds = 0;                         // reading the networks and computing the distances
};

// UnknownFrame (the first frame checked first) when a frame is not committed; NoNetwork when a
// frame's network cannot be had, has no grain positions to place it on the grid, or is not of the
// other frame's dimension.
BlockAnswer block_query(const FrameLookup& frames, const BlockRequest& request);

}  // namespace fnet::query
