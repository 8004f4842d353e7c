// The rule every analysis of a run follows, live (fnet-server) or offline (fnet-analyze store):
// frames arrive in any order, possibly repeated; each is validated and, if valid, its diagrams
// are computed; frames are settled in index order, an accepted one with its distances to the
// previous ACCEPTED frame, a rejected one with its reason; a frame still missing when a later one
// has waited for the gap timeout is skipped, and one arriving after its place was skipped is
// rejected as late.
//
// The costly work is handed out as jobs, pure functions of what they hold, so that a caller may
// run them on other threads: admit() returns a frame's diagram job, analyzed() and skip_gaps()
// return distance jobs, and the caller hands each job's outcome back. Calls on one pipeline must
// be serialized by the caller; jobs may run concurrently with them and with each other. push(),
// expire() and finish() do everything inline, for one thread. Time is given, never read, so
// that the gap timeout is a function of the arguments.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "common/analysis/analyzed_frame.hpp"
#include "common/run/run_frame.hpp"

namespace fnet {

using PipelineClock = std::chrono::steady_clock;

struct DiagramOutcome {
  std::uint32_t index = 0;
  std::optional<FrameDiagramSet> diagrams;  // empty when the frame was rejected
  std::string reason;                       // why it was rejected
};

// Validation and diagrams of one frame. The network is shared with the pipeline's frame, which
// passes it on with the accepted frame (AnalyzedFrame::network) for the store to keep.
struct DiagramJob {
  std::uint32_t index = 0;
  std::shared_ptr<const Frame> frame;
  int threads = 1;  // > 1: the two networks at once (analyze_frame)
  // > 0: a frame whose contacts per grain (contact_degeneracy) exceed it is rejected unanalyzed.
  std::size_t max_contacts_per_grain = 0;
  DiagramOutcome run() const;
};

struct DistanceOutcome {
  std::uint32_t index = 0;
  StepDistances distances;
};

// The twelve distances from the previous accepted frame to frame `index`. The diagrams are
// shared with the pipeline's frames, which never write them again.
struct DistanceJob {
  std::uint32_t index = 0;
  std::shared_ptr<const FrameDiagramSet> previous, current;
  EssentialConvention essential = EssentialConvention::floor;
  int threads = 1;   // > 1: the twelve distances shared among that many threads (step_distances)
  double delta = 0;  // > 0: each distance within that relative error instead of exact
  DistanceOutcome run() const;
};

// Frames first..last never arrived and were given up.
struct SkippedFrames {
  std::uint32_t first = 0, last = 0;
  bool operator==(const SkippedFrames&) const = default;
};

// What the pipeline settled, in index order (except a late frame's rejection, settled when it
// arrives, behind the frames settled already).
using Settlement = std::variant<std::shared_ptr<const AnalyzedFrame>, RejectedFrame, SkippedFrames>;

struct PipelineCounts {
  std::size_t accepted = 0, rejected = 0, duplicates = 0, late = 0, skipped = 0;  // rejected includes late
};

// What a frame may hold to be analyzed, besides validity (validate()) and its header's ranges
// (header_problem(), always checked).
struct FrameRules {
  std::size_t max_contacts_per_grain = 0;  // > 0: DiagramJob::max_contacts_per_grain
};

class RunPipeline {
 public:
  // refused: rejected on arrival (its header, or the caller's refusal), settled in its place.
  enum class Arrival { queued, duplicate, late, refused };
  struct Admission {
    Arrival arrival = Arrival::queued;
    std::optional<DiagramJob> job;           // present when queued
    std::vector<DistanceJob> distance_jobs;  // when refused: those its settlement made possible
  };

  explicit RunPipeline(std::chrono::milliseconds gap_timeout = std::chrono::seconds(30),
                       EssentialConvention essential = EssentialConvention::floor, FrameRules rules = {});

  // Continues a run whose frames `settled` were accepted or rejected earlier (a reloaded store),
  // the distances of the next accepted frame measured from `last_accepted` (if any). Only before
  // the first admit().
  void resume(const std::vector<std::uint32_t>& settled, std::shared_ptr<const AnalyzedFrame> last_accepted);

  // The last accepted frame, the next distances' predecessor, may be released: its diagrams
  // dropped, its index kept (a finished or idle run, a run read back from its store). A caller
  // handing back a diagram job's outcome while it is released first restores it with that frame's
  // diagrams; a frame reaching the frontier while it is still released is rejected, its distances
  // not measurable.
  void release_predecessor();
  std::optional<std::uint32_t> released_predecessor() const { return released_; }
  // Restores the released predecessor when `frame` is it (with its diagrams); else does nothing.
  void restore_predecessor(std::shared_ptr<const AnalyzedFrame> frame);

  // A frame arriving at `now`: a repeated index is a duplicate and dropped; an index whose place
  // was skipped is settled as rejected (late); a frame whose header is out of range
  // (header_problem) is refused; any other waits for its diagram job's outcome.
  Admission admit(RunFrame frame, PipelineClock::time_point now);
  // The frame of `header` arrived at `now` but was refused before it was read whole, for `reason`:
  // settled as rejected in its place (or dropped as a duplicate, or rejected as late, as admit()
  // would).
  Admission refuse(const FrameHeader& header, std::string reason, PipelineClock::time_point now);
  // Hands back a diagram job's outcome; returns the distance jobs it made possible.
  std::vector<DistanceJob> analyzed(DiagramOutcome outcome);
  // Hands back a distance job's outcome.
  void measured(const DistanceOutcome& outcome);
  // Skips the missing frames before the first waiting one once a frame after them has waited
  // for the gap timeout; returns the distance jobs this made possible.
  std::vector<DistanceJob> skip_gaps(PipelineClock::time_point now);
  // What was settled since the last call, in settlement order.
  std::vector<Settlement> take_settled();

  // One thread: admits the frame, runs its jobs inline and returns what was settled.
  std::vector<Settlement> push(RunFrame frame, PipelineClock::time_point now);
  // One thread: skip_gaps() with its jobs run inline.
  std::vector<Settlement> expire(PipelineClock::time_point now);
  // One thread, at the end of a run: nothing more will arrive, so every gap is skipped now.
  std::vector<Settlement> finish();

  // Frames admitted and not yet settled, and the bytes they hold (frame_bytes).
  std::size_t pending() const { return pending_.size(); }
  // Every frame index below it is settled (or skipped).
  std::uint32_t frontier() const { return frontier_; }
  std::size_t pending_bytes() const { return pending_bytes_; }
  std::optional<PipelineClock::time_point> oldest_arrival() const;
  const PipelineCounts& counts() const { return counts_; }

 private:
  enum class Stage { analyzing, analyzed, rejected, measuring, ready };
  struct Slot {
    Stage stage = Stage::analyzing;
    std::shared_ptr<AnalyzedFrame> frame;  // its diagrams are written once, in analyzed()
    std::string reason;
    PipelineClock::time_point arrived;
    std::size_t bytes = 0;  // of its network, while the slot holds it
  };

  // A duplicate or late arrival, settled as such; nullopt for a frame that takes a slot.
  std::optional<Admission> arrival(std::uint32_t index, const std::string& label);
  std::vector<DistanceJob> advance();
  std::optional<std::vector<DistanceJob>> skip_one(bool always, PipelineClock::time_point now);
  void settle();
  void run_inline(std::vector<DistanceJob> jobs);

  std::chrono::milliseconds gap_timeout_;
  EssentialConvention essential_;
  FrameRules rules_;
  std::set<std::uint32_t> seen_;
  std::map<std::uint32_t, Slot> pending_;
  std::uint32_t frontier_ = 0;  // the next index to resolve: every frame before it is resolved
  std::shared_ptr<const AnalyzedFrame> last_accepted_;
  std::optional<std::uint32_t> released_;  // the index of last_accepted_ once released (then null)
  std::deque<Settlement> settled_;
  PipelineCounts counts_;
  std::size_t pending_bytes_ = 0;
};

}  // namespace fnet
