// What a query reads: the committed frames of runs, their stored force networks and the members
// of an ensemble. fnet-server answers from its registry, fnet-analyze from frames it read from
// files; the queries do not know which.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/analysis/analyzed_frame.hpp"
#include "common/analysis/step_series.hpp"
#include "common/topology/frame.hpp"

namespace fnet::query {

// A run and its committed frames in index order (rows: FrameLookup::frames).
struct MemberRun {
  std::string run_id;
  std::vector<std::shared_ptr<const AnalyzedFrame>> frames;
};

class FrameLookup {
 public:
  virtual ~FrameLookup() = default;
  // A committed frame of a run with its diagrams; null when the run has no such frame (or no such run).
  virtual std::shared_ptr<const AnalyzedFrame> frame(const std::string& run, std::uint32_t index) const = 0;
  // A committed frame's row: its header, predecessor, distances and counts; its diagrams' points
  // may be absent (frame() has them). Null as frame().
  virtual std::shared_ptr<const AnalyzedFrame> row(const std::string& run, std::uint32_t index) const = 0;
  // The rows of every committed frame of a run in index order; none when there is no such run.
  virtual std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> frames(const std::string& run) const = 0;
  // The force network of a committed frame; throws NoNetwork (query_errors.hpp) naming why it
  // cannot be had.
  virtual Frame network(const std::string& run, std::uint32_t index) const = 0;
  // The runs that are members of `ensemble`, in name order, seen at one instant; empty when none.
  virtual std::vector<MemberRun> ensemble_members(const std::string& ensemble) const = 0;
};

// How a series computed from diagrams reads each frame of `run` whole (step_series.hpp).
inline WithDiagrams with_diagrams(const FrameLookup& frames, const std::string& run) {
  return [&frames, run](const AnalyzedFrame& row) {
    auto f = frames.frame(run, row.header.index);
    if (!f) throw std::logic_error("run " + run + " frame " + std::to_string(row.header.index) + " is gone");
    return f;
  };
}

}  // namespace fnet::query
