#include "server/query/pair_query.hpp"

#include <chrono>

#include "common/analysis/frame_analysis.hpp"
#include "server/query/query_errors.hpp"

namespace fnet::query {

PairAnswer pair_query(const FrameLookup& frames, const PairRequest& r) {
  const auto& [metric, dim, force, essential] = r.measure;
  const auto a = frames.frame(r.run, r.frame), b = frames.frame(r.other_run, r.other_frame);
  if (!a) throw UnknownFrame(r.run, r.frame);
  if (!b) throw UnknownFrame(r.other_run, r.other_frame);
  const auto start = std::chrono::steady_clock::now();
  PairAnswer out;
  out.distance = choice_distance(diagram_of(a->diagrams, force, dim), diagram_of(b->diagrams, force, dim), metric,
                                 essential, r.delta);
  if (r.explain_terms) {
    const Frame network_a = frames.network(r.run, r.frame), network_b = frames.network(r.other_run, r.other_frame);
    out.explained = explain(network_a, network_b, {metric.distance(), dim, force, essential, *r.explain_terms}).terms;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace fnet::query
