// The one analysis pipeline of a run, without DDS, threads or files: frames given in any order,
// repeated, invalid or missing, and the clock given explicitly.
#include "common/analysis/run_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <variant>

#include <gtest/gtest.h>

#include "common/run/frame_bounds.hpp"
#include "tests/support/small_frames.hpp"

namespace fnet {
namespace {

using namespace std::chrono_literals;
using testing::both;
using testing::frame_of;

const PipelineClock::time_point t0{};  // the pipeline never reads the clock: any origin will do

// Frame k of run "t": its forces change with k so that the distance between two frames depends
// on which two they are.
RunFrame run_frame(std::uint32_t k) {
  const double a = 1.0 + 0.37 * k, b = 2.0 + 0.11 * k * k, c = 0.5 + 0.05 * k;
  RunFrame f;
  f.header = {"t", k, 100ull * k, 0.5 * k, 0.6 + 0.01 * k, 3.0};
  f.frame = frame_of(5, {both(0, 1, a), both(1, 2, b), both(0, 2, c), both(2, 3, a + b), both(3, 4, c + 1)},
                     frame_label("t", k));
  return f;
}

RunFrame invalid_frame(std::uint32_t k) {
  RunFrame f = run_frame(k);
  f.frame.contacts[1].fn = std::numeric_limits<double>::quiet_NaN();
  return f;
}

StepDistances expected_distances(std::uint32_t from, std::uint32_t to) {
  return step_distances(analyze_frame(run_frame(from).frame), analyze_frame(run_frame(to).frame));
}

std::string validation_error(const Frame& frame) {
  try {
    validate(frame);
  } catch (const FrameError& e) {
    return e.what();
  }
  return "(valid)";
}

// The settlements by kind, in the order given.
struct Settled {
  std::vector<std::shared_ptr<const AnalyzedFrame>> accepted;
  std::vector<RejectedFrame> rejected;
  std::vector<SkippedFrames> skipped;
  std::vector<std::uint32_t> order;  // index of each accepted or rejected frame, as settled
};

void collect(Settled& out, const std::vector<Settlement>& settled) {
  for (const Settlement& s : settled) {
    if (const auto* a = std::get_if<std::shared_ptr<const AnalyzedFrame>>(&s)) {
      out.accepted.push_back(*a);
      out.order.push_back((*a)->header.index);
    } else if (const auto* r = std::get_if<RejectedFrame>(&s)) {
      out.rejected.push_back(*r);
      out.order.push_back(r->index);
    } else {
      out.skipped.push_back(std::get<SkippedFrames>(s));
    }
  }
}

std::vector<std::uint32_t> iota(std::uint32_t n) {
  std::vector<std::uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  return v;
}

// Every accepted frame k > 0 of a run without rejections or gaps measured from k - 1.
void expect_consecutive(const Settled& got, std::uint32_t n) {
  ASSERT_EQ(got.accepted.size(), n);
  EXPECT_EQ(got.order, iota(n));
  EXPECT_FALSE(got.accepted[0]->previous);
  for (std::uint32_t k = 1; k < n; ++k) {
    ASSERT_EQ(got.accepted[k]->previous, k - 1) << "frame " << k;
    EXPECT_EQ(got.accepted[k]->distances.value, expected_distances(k - 1, k).value) << "frame " << k;
    EXPECT_EQ(got.accepted[k]->header, run_frame(k).header);
  }
}

TEST(RunPipeline, FramesGivenInAShuffledOrderAreCommittedInOrder) {
  for (const unsigned seed : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE(seed);
    std::vector<std::uint32_t> arrival = iota(12);
    std::shuffle(arrival.begin(), arrival.end(), std::mt19937(seed));
    RunPipeline pipeline;
    Settled got;
    std::uint32_t settled_through = 0;  // frames 0..settled_through-1 have arrived
    std::vector<bool> arrived(12);
    for (const std::uint32_t k : arrival) {
      arrived[k] = true;
      collect(got, pipeline.push(run_frame(k), t0));
      while (settled_through < 12 && arrived[settled_through]) ++settled_through;
      // A frame is committed exactly when all of its predecessors have arrived.
      EXPECT_EQ(got.order, iota(settled_through));
      EXPECT_EQ(pipeline.pending(), std::count(arrived.begin(), arrived.end(), true) - settled_through);
    }
    expect_consecutive(got, 12);
    EXPECT_TRUE(got.skipped.empty());
    EXPECT_EQ(pipeline.counts().accepted, 12u);
  }
}

TEST(RunPipeline, JobsFinishingInAnyOrderStillCommitInOrder) {
  // As fnet-server runs it: every job on some thread, their outcomes handed back in any order.
  RunPipeline pipeline;
  std::mt19937 rng(7);
  std::vector<DiagramJob> diagram_jobs;
  for (std::uint32_t k = 0; k < 10; ++k) {
    RunPipeline::Admission a = pipeline.admit(run_frame(9 - k), t0);
    ASSERT_EQ(a.arrival, RunPipeline::Arrival::queued);
    diagram_jobs.push_back(std::move(*a.job));
  }
  std::shuffle(diagram_jobs.begin(), diagram_jobs.end(), rng);
  std::vector<DistanceJob> distance_jobs;
  for (const DiagramJob& job : diagram_jobs) {
    std::vector<DistanceJob> more = pipeline.analyzed(job.run());
    distance_jobs.insert(distance_jobs.end(), more.begin(), more.end());
  }
  ASSERT_EQ(distance_jobs.size(), 9u);
  std::shuffle(distance_jobs.begin(), distance_jobs.end(), rng);
  Settled got;
  collect(got, pipeline.take_settled());
  EXPECT_EQ(got.order, iota(1));  // frame 0 needs no distances; the rest wait for theirs
  for (const DistanceJob& job : distance_jobs) pipeline.measured(job.run());
  collect(got, pipeline.take_settled());
  expect_consecutive(got, 10);
  EXPECT_EQ(pipeline.pending(), 0u);
}

TEST(RunPipeline, DuplicatesAreCountedOnceAndDropped) {
  RunPipeline pipeline;
  Settled got;
  RunFrame impostor = run_frame(5);  // a different frame under a settled index
  impostor.header.index = 1;
  impostor.frame.label = frame_label("t", 1);
  for (RunFrame f : {run_frame(0), run_frame(2), run_frame(2), run_frame(1), impostor, run_frame(0), run_frame(3)})
    collect(got, pipeline.push(std::move(f), t0));
  expect_consecutive(got, 4);
  EXPECT_EQ(pipeline.counts().duplicates, 3u);
  EXPECT_EQ(pipeline.counts().accepted, 4u);
  // A duplicate of a frame still waiting is dropped as well, and not analyzed.
  EXPECT_EQ(pipeline.push(run_frame(5), t0).size(), 0u);
  EXPECT_EQ(pipeline.admit(run_frame(5), t0).arrival, RunPipeline::Arrival::duplicate);
  EXPECT_EQ(pipeline.pending(), 1u);
  EXPECT_EQ(pipeline.counts().duplicates, 4u);
}

TEST(RunPipeline, AnInvalidFrameIsRejectedWithItsReasonAndTheNextIsMeasuredFromTheLastAccepted) {
  RunPipeline pipeline;
  Settled got;
  for (RunFrame f : {run_frame(0), run_frame(1), invalid_frame(3), invalid_frame(2), run_frame(4)})
    collect(got, pipeline.push(std::move(f), t0));
  EXPECT_EQ(got.order, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  ASSERT_EQ(got.rejected.size(), 2u);
  EXPECT_EQ(got.rejected[0], (RejectedFrame{2, validation_error(invalid_frame(2).frame)}));
  EXPECT_EQ(got.rejected[1], (RejectedFrame{3, validation_error(invalid_frame(3).frame)}));
  EXPECT_NE(got.rejected[0].reason.find("run t frame 2"), std::string::npos) << got.rejected[0].reason;
  ASSERT_EQ(got.accepted.size(), 3u);
  EXPECT_EQ(got.accepted[2]->previous, 1u);
  EXPECT_EQ(got.accepted[2]->distances.value, expected_distances(1, 4).value);
  EXPECT_NE(expected_distances(1, 4).value, expected_distances(3, 4).value);  // the check can tell them apart
  EXPECT_EQ(pipeline.counts().rejected, 2u);
}

TEST(RunPipeline, AFirstFrameRejectedLeavesTheNextWithoutPredecessor) {
  RunPipeline pipeline;
  Settled got;
  collect(got, pipeline.push(invalid_frame(0), t0));
  collect(got, pipeline.push(run_frame(1), t0));
  collect(got, pipeline.push(run_frame(2), t0));
  ASSERT_EQ(got.accepted.size(), 2u);
  EXPECT_FALSE(got.accepted[0]->previous);
  EXPECT_EQ(got.accepted[1]->previous, 1u);
}

TEST(RunPipeline, AMissingFrameIsSkippedAfterTheGapTimeoutNotBefore) {
  RunPipeline pipeline(10s);
  Settled got;
  collect(got, pipeline.push(run_frame(0), t0));
  collect(got, pipeline.push(run_frame(2), t0 + 1s));  // waits for 1 from t0 + 1 s
  collect(got, pipeline.push(run_frame(3), t0 + 5s));
  collect(got, pipeline.expire(t0 + 1s + 10s - 1ms));
  EXPECT_EQ(got.order, iota(1));
  EXPECT_TRUE(got.skipped.empty());
  EXPECT_EQ(pipeline.pending(), 2u);
  EXPECT_EQ(pipeline.oldest_arrival(), t0 + 1s);
  collect(got, pipeline.expire(t0 + 1s + 10s));
  EXPECT_EQ(got.skipped, (std::vector<SkippedFrames>{{1, 1}}));
  EXPECT_EQ(got.order, (std::vector<std::uint32_t>{0, 2, 3}));
  EXPECT_EQ(got.accepted[1]->previous, 0u);
  EXPECT_EQ(got.accepted[1]->distances.value, expected_distances(0, 2).value);
  EXPECT_EQ(got.accepted[2]->previous, 2u);
  EXPECT_EQ(pipeline.counts().skipped, 1u);
  EXPECT_EQ(pipeline.pending(), 0u);
}

TEST(RunPipeline, TheGapTimeoutDoesNotSkipAFrameBeingAnalyzed) {
  // Frame 1 arrived but its diagrams are still being computed: no gap, however long it takes.
  RunPipeline pipeline(10s);
  Settled got;
  collect(got, pipeline.push(run_frame(0), t0));
  RunPipeline::Admission one = pipeline.admit(run_frame(1), t0);
  collect(got, pipeline.push(run_frame(2), t0));
  collect(got, pipeline.expire(t0 + 1h));
  EXPECT_TRUE(got.skipped.empty());
  std::vector<DistanceJob> jobs = pipeline.analyzed(one.job->run());
  for (const DistanceJob& job : jobs) pipeline.measured(job.run());
  collect(got, pipeline.take_settled());
  expect_consecutive(got, 3);
}

TEST(RunPipeline, SeveralGapsAreSkippedTogetherAndAFrameArrivingAfterItsSkipIsRejectedAsLate) {
  RunPipeline pipeline(10s);
  Settled got;
  for (const std::uint32_t k : {0u, 3u, 6u}) collect(got, pipeline.push(run_frame(k), t0));
  collect(got, pipeline.expire(t0 + 10s));
  EXPECT_EQ(got.skipped, (std::vector<SkippedFrames>{{1, 2}, {4, 5}}));
  EXPECT_EQ(got.order, (std::vector<std::uint32_t>{0, 3, 6}));
  EXPECT_EQ(got.accepted[2]->previous, 3u);
  EXPECT_EQ(pipeline.counts().skipped, 4u);

  collect(got, pipeline.push(run_frame(4), t0 + 11s));
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(got.rejected[0], (RejectedFrame{4, "run t frame 4: arrived after the gap timeout had skipped it"}));
  EXPECT_EQ(pipeline.counts().late, 1u);
  EXPECT_EQ(pipeline.counts().rejected, 1u);
  EXPECT_EQ(pipeline.push(run_frame(4), t0 + 12s).size(), 0u);  // late once, then a duplicate
  EXPECT_EQ(pipeline.counts().duplicates, 1u);
  collect(got, pipeline.push(run_frame(7), t0 + 13s));  // the late frame changed no predecessor
  EXPECT_EQ(got.accepted.back()->previous, 6u);
  EXPECT_EQ(got.accepted.back()->distances.value, expected_distances(6, 7).value);
}

TEST(RunPipeline, FinishSkipsEveryGapAtTheEndOfARun) {
  RunPipeline pipeline(10s);
  Settled got;
  for (const std::uint32_t k : {4u, 1u, 7u, 2u}) collect(got, pipeline.push(run_frame(k), t0));
  EXPECT_TRUE(got.order.empty());
  collect(got, pipeline.finish());
  EXPECT_EQ(got.skipped, (std::vector<SkippedFrames>{{0, 0}, {3, 3}, {5, 6}}));
  EXPECT_EQ(got.order, (std::vector<std::uint32_t>{1, 2, 4, 7}));
  EXPECT_EQ(got.accepted[2]->previous, 2u);
  EXPECT_EQ(got.accepted[3]->previous, 4u);
  EXPECT_EQ(got.accepted[3]->distances.value, expected_distances(4, 7).value);
}

TEST(RunPipeline, AResumedRunContinuesFromItsLastAcceptedFrame) {
  auto last = std::make_shared<AnalyzedFrame>();
  last->header = run_frame(2).header;
  last->diagrams = analyze_frame(run_frame(2).frame);
  RunPipeline pipeline;
  pipeline.resume({0, 1, 2, 3}, last);  // frame 3 was rejected
  Settled got;
  collect(got, pipeline.push(run_frame(1), t0));
  EXPECT_EQ(pipeline.counts().duplicates, 1u);
  collect(got, pipeline.push(run_frame(4), t0));
  ASSERT_EQ(got.accepted.size(), 1u);
  EXPECT_EQ(got.accepted[0]->previous, 2u);
  EXPECT_EQ(got.accepted[0]->distances.value, expected_distances(2, 4).value);
}

}  // namespace
}  // namespace fnet

namespace fnet {
namespace {

// The frames of a run whose frame 2 has a header no series can use: each value alone.
TEST(RunPipeline, AFrameWithAHeaderOutOfRangeIsRejectedInItsPlaceAndTheNextIsMeasuredFromTheLastAccepted) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::function<void(FrameHeader&)>, std::string>> planted = {
      {[&](FrameHeader& h) { h.rho = nan; }, "rho = nan is not a finite number in [0, 2]"},
      {[](FrameHeader& h) { h.rho = 1e300; }, "rho = 1e+300 is not a finite number in [0, 2]"},
      {[](FrameHeader& h) { h.rho = -0.1; }, "rho = -0.1 is not a finite number in [0, 2]"},
      {[&](FrameHeader& h) { h.z = inf; }, "z = inf is not a finite number in [0, 48]"},
      {[](FrameHeader& h) { h.z = 1e9; }, "z = 1e+09 is not a finite number in [0, 48]"},
      {[&](FrameHeader& h) { h.time = nan; }, "time = nan is not a finite number >= 0"},
      {[](FrameHeader& h) { h.time = -1; }, "time = -1 is not a finite number >= 0"},
      {[](FrameHeader& h) { h.step = (1ull << 53) + 1; }, "step = 9007199254740993 exceeds 2^53"},
  };
  for (const auto& [plant, reason] : planted) {
    SCOPED_TRACE(reason);
    RunPipeline pipeline;
    Settled got;
    for (std::uint32_t k = 0; k < 4; ++k) {
      RunFrame f = run_frame(k);
      if (k == 2) plant(f.header);
      collect(got, pipeline.push(std::move(f), t0));
    }
    EXPECT_EQ(got.order, iota(4));
    ASSERT_EQ(got.rejected.size(), 1u);
    EXPECT_EQ(got.rejected[0].index, 2u);
    EXPECT_EQ(got.rejected[0].reason.rfind("run t frame 2: header rejected: " + reason, 0), 0u)
        << got.rejected[0].reason;
    ASSERT_EQ(got.accepted.size(), 3u);
    EXPECT_EQ(got.accepted[2]->previous, 1u);
    EXPECT_EQ(got.accepted[2]->distances.value, expected_distances(1, 3).value);
    EXPECT_EQ(pipeline.counts().rejected, 1u);
  }
}

TEST(RunPipeline, AFrameRefusedUnreadIsSettledInItsPlaceAfterItsPredecessors) {
  RunPipeline pipeline;
  Settled got;
  collect(got, pipeline.push(run_frame(0), t0));
  RunPipeline::Admission a = pipeline.admit(run_frame(1), t0);
  ASSERT_TRUE(a.job);
  RunPipeline::Admission r = pipeline.refuse(run_frame(2).header, "run t frame 2: too large", t0);
  EXPECT_EQ(r.arrival, RunPipeline::Arrival::refused);
  EXPECT_TRUE(r.distance_jobs.empty());  // frame 1 is still being analyzed
  EXPECT_EQ(pipeline.pending(), 2u);
  collect(got, pipeline.take_settled());
  EXPECT_EQ(got.order, iota(1));
  for (const DistanceJob& job : pipeline.analyzed(a.job->run())) pipeline.measured(job.run());
  collect(got, pipeline.take_settled());
  EXPECT_EQ(got.order, iota(3));
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(got.rejected[0].reason, "run t frame 2: too large");
  // A refusal repeated is a duplicate.
  EXPECT_EQ(pipeline.refuse(run_frame(2).header, "again", t0).arrival, RunPipeline::Arrival::duplicate);
  // Frame 3 after a refused frame 2: measured from frame 1.
  collect(got, pipeline.push(run_frame(3), t0));
  ASSERT_EQ(got.accepted.size(), 3u);
  EXPECT_EQ(got.accepted[2]->previous, 1u);
}

TEST(RunPipeline, AFrameRefusedAfterItsSuccessorWasAnalyzedReleasesTheSuccessorsDistances) {
  RunPipeline pipeline;
  Settled got;
  collect(got, pipeline.push(run_frame(0), t0));
  collect(got, pipeline.push(run_frame(2), t0));  // waits for frame 1
  EXPECT_EQ(got.order, iota(1));
  RunPipeline::Admission r = pipeline.refuse(run_frame(1).header, "run t frame 1: too large", t0);
  ASSERT_EQ(r.distance_jobs.size(), 1u);
  for (const DistanceJob& job : r.distance_jobs) pipeline.measured(job.run());
  collect(got, pipeline.take_settled());
  EXPECT_EQ(got.order, iota(3));
  EXPECT_EQ(got.accepted[1]->previous, 0u);
  EXPECT_EQ(got.accepted[1]->distances.value, expected_distances(0, 2).value);
}

TEST(RunPipeline, PendingBytesCountTheFramesHeldAndFallToZeroOnceSettled) {
  RunPipeline pipeline;
  const RunFrame f = run_frame(0);
  const std::size_t one = frame_bytes(f.frame.particle_count, f.frame.contacts.size());
  EXPECT_EQ(one, 5 * sizeof(Particle) + 5 * sizeof(Contact));
  RunPipeline::Admission a0 = pipeline.admit(run_frame(0), t0);
  RunPipeline::Admission a1 = pipeline.admit(invalid_frame(1), t0);
  EXPECT_EQ(pipeline.pending_bytes(), 2 * one);
  pipeline.analyzed(a1.job->run());  // rejected: its network is let go at once
  EXPECT_EQ(pipeline.pending_bytes(), one);
  pipeline.analyzed(a0.job->run());
  EXPECT_EQ(pipeline.pending_bytes(), 0u);
  EXPECT_EQ(pipeline.pending(), 0u);
}

// Every pair of 30 grains in contact: 29 contacts per grain; a packing reaches 5 (2D) or 12 (3D).
TEST(RunPipeline, AFrameWithMoreContactsPerGrainThanTheBoundIsRejectedUnanalyzed) {
  std::vector<Contact> clique;
  for (std::int64_t i = 0; i < 30; ++i)
    for (std::int64_t j = i + 1; j < 30; ++j) clique.push_back(both(i, j, 1.0 + 0.01 * static_cast<double>(i + j)));
  for (const std::size_t bound : {std::size_t{24}, std::size_t{28}, std::size_t{29}, std::size_t{0}}) {
    SCOPED_TRACE(bound);
    RunPipeline pipeline(30s, EssentialConvention::floor, FrameRules{.max_contacts_per_grain = bound});
    RunFrame f = run_frame(0);
    f.frame = frame_of(30, clique, frame_label("t", 0));
    Settled got;
    collect(got, pipeline.push(std::move(f), t0));
    if (bound == 0 || bound >= 29) {
      EXPECT_EQ(got.accepted.size(), 1u);
    } else {
      ASSERT_EQ(got.rejected.size(), 1u);
      EXPECT_EQ(got.rejected[0].reason.rfind("run t frame 0: 29 contacts per grain", 0), 0u) << got.rejected[0].reason;
      EXPECT_NE(got.rejected[0].reason.find("exceed the bound of " + std::to_string(bound)), std::string::npos);
    }
  }
  // The LAMMPS-like frames of this test pass the default bound.
  RunPipeline pipeline(30s, EssentialConvention::floor, FrameRules{.max_contacts_per_grain = 24});
  Settled got;
  collect(got, pipeline.push(run_frame(0), t0));
  EXPECT_EQ(got.accepted.size(), 1u);
}

}  // namespace
}  // namespace fnet
