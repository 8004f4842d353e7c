#include "common/distance/essential_convention.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fnet {

std::string_view to_string(EssentialConvention convention) {
  switch (convention) {
    case EssentialConvention::floor:
      return "floor";
    case EssentialConvention::sentinel:
      return "sentinel";
    case EssentialConvention::separate:
      return "separate";
  }
  return "floor";
}

EssentialConvention parse_essential_convention(std::string_view text) {
  if (text == "floor") return EssentialConvention::floor;
  if (text == "sentinel") return EssentialConvention::sentinel;
  if (text == "separate") return EssentialConvention::separate;
  throw std::invalid_argument("unknown convention for never-dying classes '" + std::string(text) +
                              "' (expected floor, sentinel or separate)");
}

namespace {

// sources == nullptr: the view alone, as every distance needs it.
ConventionView make_view(const Diagram& diagram, EssentialConvention convention, ViewSources* sources) {
  ConventionView view;
  view.points.reserve(diagram.size());
  for (std::size_t k = 0; k < diagram.size(); ++k) {
    const PersistencePoint& p = diagram[k];
    if (!std::isfinite(p.birth) || !std::isfinite(p.death))
      throw std::invalid_argument("diagram point with a non-finite coordinate");
    PlanePoint q{p.birth, p.death};
    if (p.death == kNeverDies) {
      if (convention == EssentialConvention::separate) {
        view.essential_births.push_back(p.birth);
        if (sources) sources->essential.push_back(static_cast<std::uint32_t>(k));
        continue;
      }
      if (convention == EssentialConvention::floor) q.y = 0;
    }
    if (q.x != q.y) {
      view.points.push_back(q);
      if (sources) sources->points.push_back(static_cast<std::uint32_t>(k));
    }
  }
  if (sources) {
    std::stable_sort(sources->essential.begin(), sources->essential.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return diagram[a].birth < diagram[b].birth; });
    for (std::size_t k = 0; k < sources->essential.size(); ++k)
      view.essential_births[k] = diagram[sources->essential[k]].birth;
  } else {
    std::sort(view.essential_births.begin(), view.essential_births.end());
  }
  return view;
}

}  // namespace

ConventionView apply_convention(const Diagram& diagram, EssentialConvention convention) {
  return make_view(diagram, convention, nullptr);
}

ConventionView apply_convention(const Diagram& diagram, EssentialConvention convention, ViewSources& sources) {
  sources = {};
  return make_view(diagram, convention, &sources);
}

std::string essential_count_mismatch(const ConventionView& a, const ConventionView& b) {
  if (a.essential_births.size() == b.essential_births.size()) return {};
  return "separate convention: " + std::to_string(a.essential_births.size()) + " vs " +
         std::to_string(b.essential_births.size()) +
         " never-dying classes; they can only match among themselves, so the distance is infinite";
}

}  // namespace fnet
