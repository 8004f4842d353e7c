#include "server/query/block_query.hpp"

#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>

#include "server/query/query_errors.hpp"

namespace fnet::query {

BlockAnswer block_query(const FrameLookup& frames, const BlockRequest& r) {
  const auto& [metric, dim, force, essential] = r.measure;
  if (!frames.row(r.run, r.frame)) throw UnknownFrame(r.run, r.frame);
  if (!frames.row(r.run, r.other_frame)) throw UnknownFrame(r.run, r.other_frame);
  const auto start = std::chrono::steady_clock::now();
  const Frame a = frames.network(r.run, r.frame), b = frames.network(r.run, r.other_frame);
  if (a.dimension != b.dimension)
    throw NoNetwork(r.run, r.other_frame,
                    "frame " + std::to_string(r.other_frame) + " is " + std::to_string(b.dimension) + "D and frame " +
                        std::to_string(r.frame) + " " + std::to_string(a.dimension) +
                        "D: blocks compare the same grid over two frames of one dimension");
  const auto split = [&](const Frame& f, std::uint32_t index) {
    try {
      return split_into_blocks(f, r.k);
    } catch (const std::invalid_argument& e) {  // a stored frame without its grains' positions
      throw NoNetwork(r.run, index, e.what());
    }
  };
  BlockAnswer out;
  out.cells = split(a, r.frame);
  out.other_cells = split(b, r.other_frame);
  out.distances = block_distances(out.cells, out.other_cells, metric.distance(), dim, force, essential);
  const auto key = [&](std::size_t c) {
    const DistanceResult& d = out.distances[c].distance;
    return d.infinite ? std::numeric_limits<double>::infinity() : d.value;
  };
  for (std::size_t c = 0; c < out.distances.size(); ++c)
    if (key(c) > key(out.largest)) out.largest = c;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace fnet::query
