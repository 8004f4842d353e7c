#include "common/distance/diagram_matching.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "common/distance/linf_kdtree.hpp"

namespace fnet {

MatchingBuilder::MatchingBuilder(const ConventionView& va, const ViewSources& sa, std::size_t size_a,
                                 const ConventionView& vb, const ViewSources& sb, std::size_t size_b)
    : va_(va), vb_(vb), sa_(sa), sb_(sb), used_a_(size_a, 0), used_b_(size_b, 0) {
  out_.pairs.reserve(size_a + size_b);
}

void MatchingBuilder::pair(std::uint32_t i, std::uint32_t j) {
  const std::uint32_t a = sa_.points[i], b = sb_.points[j];
  used_a_[a] = used_b_[b] = 1;
  out_.pairs.push_back({a, b, linf_distance(va_.points[i], vb_.points[j])});
}

void MatchingBuilder::a_to_diagonal(std::uint32_t i) {
  const std::uint32_t a = sa_.points[i];
  used_a_[a] = 1;
  out_.pairs.push_back({a, -1, std::fabs(va_.points[i].x - va_.points[i].y) / 2});
}

void MatchingBuilder::b_to_diagonal(std::uint32_t j) {
  const std::uint32_t b = sb_.points[j];
  used_b_[b] = 1;
  out_.pairs.push_back({-1, b, std::fabs(vb_.points[j].x - vb_.points[j].y) / 2});
}

void MatchingBuilder::essentials() {
  if (va_.essential_births.size() != vb_.essential_births.size())
    throw std::logic_error("matching: essential classes of unequal counts");
  for (std::size_t k = 0; k < va_.essential_births.size(); ++k) {
    const std::uint32_t a = sa_.essential[k], b = sb_.essential[k];
    used_a_[a] = used_b_[b] = 1;
    out_.pairs.push_back({a, b, std::fabs(va_.essential_births[k] - vb_.essential_births[k])});
  }
}

void MatchingBuilder::all_to_diagonal() {
  for (std::uint32_t i = 0; i < va_.points.size(); ++i) a_to_diagonal(i);
  for (std::uint32_t j = 0; j < vb_.points.size(); ++j) b_to_diagonal(j);
}

DiagramMatching MatchingBuilder::finish() {
  for (std::size_t a = 0; a < used_a_.size(); ++a)
    if (!used_a_[a]) out_.pairs.push_back({static_cast<std::int64_t>(a), -1, 0.0});
  for (std::size_t b = 0; b < used_b_.size(); ++b)
    if (!used_b_[b]) out_.pairs.push_back({-1, static_cast<std::int64_t>(b), 0.0});
  out_.longest = 0;
  for (std::size_t k = 1; k < out_.pairs.size(); ++k)
    if (out_.pairs[k].length > out_.pairs[out_.longest].length) out_.longest = k;
  return std::move(out_);
}

ConventionView view_for(const Diagram& diagram, EssentialConvention convention, ViewSources* sources) {
  return sources ? apply_convention(diagram, convention, *sources) : apply_convention(diagram, convention);
}

DiagramMatching identity_matching(const Diagram& a, const Diagram& b, EssentialConvention convention) {
  ViewSources sa, sb;
  const ConventionView va = apply_convention(a, convention, sa), vb = apply_convention(b, convention, sb);
  if (va.points.size() != vb.points.size()) throw std::logic_error("identity matching of unequal diagrams");
  const auto by_point = [](const ConventionView& v) {
    std::vector<std::uint32_t> order(v.points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
      return v.points[p].x != v.points[q].x ? v.points[p].x < v.points[q].x : v.points[p].y < v.points[q].y;
    });
    return order;
  };
  const auto oa = by_point(va), ob = by_point(vb);
  MatchingBuilder builder(va, sa, a.size(), vb, sb, b.size());
  builder.essentials();
  for (std::size_t k = 0; k < oa.size(); ++k) builder.pair(oa[k], ob[k]);
  return builder.finish();
}

}  // namespace fnet
