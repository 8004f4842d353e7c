#include "server/query/curve_query.hpp"

#include "common/analysis/jamming.hpp"
#include "common/run/frame_bounds.hpp"

namespace fnet::query {
namespace {

const std::vector<StepValue>& steps_of(const FrameLookup& frames, const MemberRun& member, const StepQuery& query,
                                       std::map<std::string, std::vector<StepValue>>& cache) {
  std::vector<StepValue>& steps = cache[member.run_id];
  // Frames are committed in index order, so a run's values only ever grow at the end.
  const bool prefix = steps.size() <= member.frames.size() &&
                      (steps.empty() || member.frames[steps.size() - 1]->header.index == steps.back().index);
  if (!prefix) steps.clear();
  append_step_values(member.frames, query, steps.size(), steps, with_diagrams(frames, member.run_id));
  return steps;
}

}  // namespace

Curve compute_curve(const FrameLookup& frames, const CurveRequest& r, StepCache& cache) {
  std::vector<MemberRun> members;
  if (r.run.empty()) {
    members = frames.ensemble_members(r.ensemble);
  } else if (auto committed = frames.frames(r.run)) {
    members.push_back({r.run, std::move(*committed)});
  }
  Curve c;
  for (MemberRun& m : members)
    std::erase_if(m.frames, [&](const std::shared_ptr<const AnalyzedFrame>& f) {
      const std::string problem = header_problem(f->header);
      if (!problem.empty()) c.left_out.push_back(frame_label(m.run_id, f->header.index) + ": left out: " + problem);
      return !problem.empty();
    });
  std::vector<CurveSample> numerator, denominator;
  for (const MemberRun& m : members) {
    double shift = 0;
    if (r.axis == CurveAxis::rho_minus_rho_j) {
      std::vector<double> rho, z;
      for (const auto& f : m.frames) {
        rho.push_back(f->header.rho);
        z.push_back(f->header.z);
      }
      const auto rho_j = jamming_density(rho, z);
      if (!rho_j) {
        c.runs_without_rho_j.push_back(m.run_id);
        continue;
      }
      shift = *rho_j;
    }
    // A run's index in `runs` (its place in name order) names its samples' realization.
    const std::size_t run = c.runs.size();
    c.runs.push_back(m.run_id);
    const auto add = [&](std::vector<CurveSample>& to, const std::vector<StepValue>& steps) {
      const std::vector<CurveSample> s = curve_samples(steps, shift, run);
      to.insert(to.end(), s.begin(), s.end());
    };
    add(numerator, steps_of(frames, m, r.measure.query, cache.numerator));
    if (r.measure.denominator) add(denominator, steps_of(frames, m, *r.measure.denominator, cache.denominator));
  }
  c.bins = bin_curve(numerator, r.binning);
  if (r.measure.denominator) c.bins = ratio_curve(c.bins, bin_curve(denominator, r.binning));
  return c;
}

}  // namespace fnet::query
