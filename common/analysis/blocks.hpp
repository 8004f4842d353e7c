// Where a force network changed (the paper's Tables II, III): a frame's network cut into the cells
// of a k x k grid over its domain (k x k x k in a 3D frame), each cell's diagrams, and the
// distances cell by cell between two frames.
//
// The domain of a frame is the bounding box of its grains' discs (x ± r, y ± r), or of its
// spheres in 3D (also z ± r): the walls move during a compression, so the grid follows the packing
// rather than a fixed box. Cell (row, col) spans [x_lo + col·w/k, x_lo + (col + 1)·w/k] ×
// [y_lo + row·h/k, ...], and in 3D cell (layer, row, col) also [z_lo + layer·t/k, ...]; row 0 is
// the lowest y, col 0 the lowest x, layer 0 the lowest z. A contact belongs to the cell holding its
// contact point, the point on the line of centres at distance r_i from grain i's centre; a point on
// a face between two cells goes to the cell with the larger index (a domain of zero extent along
// an axis has a single column, row or layer there). A cell's network is its contacts with their grains, plus the grains
// that touch nothing (rattlers) whose centre lies in the cell, so that k = 1 is the whole frame. Each cell's network is
// normalized by its own mean force, like a frame's: a cell's diagrams do not depend on the forces elsewhere.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/analysis/frame_analysis.hpp"
#include "common/topology/frame.hpp"

namespace fnet {

inline constexpr int kMinBlocks = 1, kMaxBlocks = 16;

struct BlockDomain {
  double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
  double z_lo = 0, z_hi = 0;  // 0, 0 in 2D
};

struct BlockCell {
  int layer = 0, row = 0, col = 0;    // layer 0 in 2D
  std::array<double, 6> bounds{};     // x_lo, x_hi, y_lo, y_hi, z_lo, z_hi (z 0, 0 in 2D)
  std::vector<std::uint32_t> grains;  // indices into the frame's particles, ascending
  std::vector<std::size_t> contacts;  // indices into the frame's contacts, ascending
  Frame network;                      // the cell's network, its grains renumbered 0..n-1 in that order
};

// The cells of a k x k grid, row-major (cell row·k + col); of a 3D frame, k x k x k cells layer by
// layer (cell (layer·k + row)·k + col). The frame must have passed validate()
// and have its particle table; throws std::invalid_argument for k outside [kMinBlocks, kMaxBlocks]
// or a frame without particles.
BlockDomain block_domain(const Frame& frame);
std::vector<BlockCell> split_into_blocks(const Frame& frame, int k);

// The diagrams of one cell's network for one force.
FrameDiagrams block_diagrams(const BlockCell& cell, ForceKind force);

struct BlockDistance {
  DistanceResult distance;
  std::size_t points_a = 0, points_b = 0;  // points of the compared diagrams
};

// Cell by cell distances between the same grid over two frames (cells of equal k), in cell order.
std::vector<BlockDistance> block_distances(const std::vector<BlockCell>& a, const std::vector<BlockCell>& b,
                                           DistanceMetric metric, int dim, ForceKind force,
                                           EssentialConvention essential = EssentialConvention::floor);

}  // namespace fnet
