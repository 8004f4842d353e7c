#include "common/analysis/run_pipeline.hpp"

#include <algorithm>
#include <exception>
#include <utility>

#include "common/run/frame_bounds.hpp"
#include "common/topology/contact_degeneracy.hpp"

namespace fnet {

DiagramOutcome DiagramJob::run() const {
  DiagramOutcome out{index, std::nullopt, {}};
  try {
    validate(*frame);
    if (max_contacts_per_grain > 0) {
      if (const std::size_t k = contact_degeneracy(*frame); k > max_contacts_per_grain)
        throw FrameError(frame->label + ": " + std::to_string(k) +
                         " contacts per grain (the contact graph's degeneracy: some set of grains has each "
                         "touching that many others of the set) exceed the bound of " +
                         std::to_string(max_contacts_per_grain) +
                         "; grains that do not overlap reach at most 5 (disks) "
                         "or 12 (spheres)");
    }
    out.diagrams = analyze_frame(*frame, threads);
  } catch (const std::exception& e) {
    out.reason = e.what();
  }
  return out;
}

DistanceOutcome DistanceJob::run() const {
  return {index, step_distances(*previous, *current, essential, threads, delta)};
}

RunPipeline::RunPipeline(std::chrono::milliseconds gap_timeout, EssentialConvention essential, FrameRules rules)
    : gap_timeout_(gap_timeout), essential_(essential), rules_(rules) {}

void RunPipeline::resume(const std::vector<std::uint32_t>& settled,
                         std::shared_ptr<const AnalyzedFrame> last_accepted) {
  seen_.insert(settled.begin(), settled.end());
  frontier_ = seen_.empty() ? 0 : *seen_.rbegin() + 1;
  last_accepted_ = std::move(last_accepted);
}

void RunPipeline::release_predecessor() {
  if (last_accepted_) released_ = last_accepted_->header.index;
  last_accepted_.reset();
}

void RunPipeline::restore_predecessor(std::shared_ptr<const AnalyzedFrame> frame) {
  if (!released_ || !frame || frame->header.index != *released_) return;
  last_accepted_ = std::move(frame);
  released_.reset();
}

std::optional<RunPipeline::Admission> RunPipeline::arrival(std::uint32_t index, const std::string& label) {
  if (!seen_.insert(index).second) {
    ++counts_.duplicates;
    return Admission{Arrival::duplicate, std::nullopt, {}};
  }
  if (index < frontier_) {  // its place was given up after the gap timeout
    ++counts_.late;
    ++counts_.rejected;
    settled_.push_back(RejectedFrame{index, label + ": arrived after the gap timeout had skipped it"});
    return Admission{Arrival::late, std::nullopt, {}};
  }
  return std::nullopt;
}

RunPipeline::Admission RunPipeline::admit(RunFrame frame, PipelineClock::time_point now) {
  const std::uint32_t index = frame.header.index;
  if (const std::string problem = header_problem(frame.header); !problem.empty())
    return refuse(frame.header, frame.frame.label + ": header rejected: " + problem, now);
  if (auto settled = arrival(index, frame.frame.label)) return std::move(*settled);
  Slot& slot = pending_[index];
  slot.frame = std::make_shared<AnalyzedFrame>();
  slot.frame->header = frame.header;
  slot.frame->dimension = frame.frame.dimension;
  slot.bytes = frame_bytes(frame.frame.particle_count, frame.frame.contacts.size());
  pending_bytes_ += slot.bytes;
  slot.frame->network = std::make_shared<const Frame>(std::move(frame.frame));
  slot.arrived = now;
  DiagramJob job{index, slot.frame->network};
  job.max_contacts_per_grain = rules_.max_contacts_per_grain;
  return {Arrival::queued, std::move(job), {}};
}

RunPipeline::Admission RunPipeline::refuse(const FrameHeader& header, std::string reason,
                                           PipelineClock::time_point now) {
  if (auto settled = arrival(header.index, frame_label(header.run_id, header.index))) return std::move(*settled);
  Slot& slot = pending_[header.index];
  slot.stage = Stage::rejected;
  slot.reason = std::move(reason);
  slot.arrived = now;
  return {Arrival::refused, std::nullopt, advance()};
}

std::vector<DistanceJob> RunPipeline::analyzed(DiagramOutcome outcome) {
  Slot& slot = pending_.at(outcome.index);
  if (outcome.diagrams) {
    slot.frame->diagrams = std::move(*outcome.diagrams);
    slot.stage = Stage::analyzed;
  } else {
    slot.reason = std::move(outcome.reason);
    slot.stage = Stage::rejected;
    slot.frame->network.reset();
    pending_bytes_ -= std::exchange(slot.bytes, 0);
  }
  return advance();
}

void RunPipeline::measured(const DistanceOutcome& outcome) {
  Slot& slot = pending_.at(outcome.index);
  slot.frame->distances = outcome.distances;
  slot.stage = Stage::ready;
  settle();
}

// Resolves the frames at the frontier in index order: an analyzed frame learns its predecessor,
// the last accepted frame, and becomes the predecessor of the next.
std::vector<DistanceJob> RunPipeline::advance() {
  std::vector<DistanceJob> jobs;
  for (auto it = pending_.find(frontier_); it != pending_.end() && it->second.stage != Stage::analyzing;
       it = pending_.find(++frontier_)) {
    Slot& slot = it->second;
    if (slot.stage != Stage::analyzed) continue;  // rejected: the predecessor stays as it was
    if (released_) {                              // not restored: its distances cannot be measured
      slot.stage = Stage::rejected;
      slot.reason = frame_label(slot.frame->header.run_id, frontier_) + ": the diagrams of frame " +
                    std::to_string(*released_) + ", its predecessor, could not be read back";
      slot.frame->network.reset();
      pending_bytes_ -= std::exchange(slot.bytes, 0);
      continue;
    }
    if (last_accepted_) {
      slot.frame->previous = last_accepted_->header.index;
      // Aliasing pointers: the diagrams stay owned by their frames.
      jobs.push_back({frontier_, std::shared_ptr<const FrameDiagramSet>(last_accepted_, &last_accepted_->diagrams),
                      std::shared_ptr<const FrameDiagramSet>(slot.frame, &slot.frame->diagrams), essential_});
      slot.stage = Stage::measuring;
    } else {
      slot.stage = Stage::ready;
    }
    // The next frame's predecessor: its index and diagrams, not its network (the store keeps it).
    auto last = std::make_shared<AnalyzedFrame>();
    last->header = slot.frame->header;
    last->diagrams = slot.frame->diagrams;
    last_accepted_ = std::move(last);
  }
  settle();
  return jobs;
}

// Settles the leading run of resolved frames, so that what is settled is in index order. A frame
// beyond the frontier is not resolved even if rejected already: a frame before it is missing.
void RunPipeline::settle() {
  while (!pending_.empty() && pending_.begin()->first < frontier_) {
    const auto it = pending_.begin();
    Slot& slot = it->second;
    if (slot.stage == Stage::rejected) {
      settled_.push_back(RejectedFrame{it->first, std::move(slot.reason)});
      ++counts_.rejected;
    } else if (slot.stage == Stage::ready) {
      settled_.push_back(std::shared_ptr<const AnalyzedFrame>(std::move(slot.frame)));
      ++counts_.accepted;
    } else {
      break;  // still analyzing or measuring
    }
    pending_bytes_ -= slot.bytes;
    pending_.erase(it);
  }
}

std::vector<DistanceJob> RunPipeline::skip_gaps(PipelineClock::time_point now) {
  std::vector<DistanceJob> jobs;
  while (std::optional<std::vector<DistanceJob>> more = skip_one(false, now))
    jobs.insert(jobs.end(), more->begin(), more->end());
  return jobs;
}

// A gap is the frontier missing while later frames wait. Frames before the frontier still being
// measured are no gap, but a gap after them waits until they are settled, so that what is settled
// stays in index order.
std::optional<std::vector<DistanceJob>> RunPipeline::skip_one(bool always, PipelineClock::time_point now) {
  if (pending_.empty() || pending_.begin()->first <= frontier_) return std::nullopt;
  if (!always && now - *oldest_arrival() < gap_timeout_) return std::nullopt;
  const std::uint32_t next = pending_.begin()->first;
  settled_.push_back(SkippedFrames{frontier_, next - 1});
  counts_.skipped += next - frontier_;
  frontier_ = next;
  return advance();
}

std::vector<Settlement> RunPipeline::take_settled() {
  std::vector<Settlement> out(std::make_move_iterator(settled_.begin()), std::make_move_iterator(settled_.end()));
  settled_.clear();
  return out;
}

std::optional<PipelineClock::time_point> RunPipeline::oldest_arrival() const {
  std::optional<PipelineClock::time_point> oldest;
  for (const auto& [index, slot] : pending_)
    if (!oldest || slot.arrived < *oldest) oldest = slot.arrived;
  return oldest;
}

void RunPipeline::run_inline(std::vector<DistanceJob> jobs) {
  for (const DistanceJob& job : jobs) measured(job.run());
}

std::vector<Settlement> RunPipeline::push(RunFrame frame, PipelineClock::time_point now) {
  Admission admission = admit(std::move(frame), now);
  if (admission.job) run_inline(analyzed(admission.job->run()));
  run_inline(std::move(admission.distance_jobs));
  return take_settled();
}

std::vector<Settlement> RunPipeline::expire(PipelineClock::time_point now) {
  while (std::optional<std::vector<DistanceJob>> jobs = skip_one(false, now)) run_inline(std::move(*jobs));
  return take_settled();
}

std::vector<Settlement> RunPipeline::finish() {
  while (std::optional<std::vector<DistanceJob>> jobs = skip_one(true, {})) run_inline(std::move(*jobs));
  return take_settled();
}

}  // namespace fnet
