#include "client/watch_view.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "client/value_text.hpp"
#include "common/analysis/metric_vocabulary.hpp"

namespace fnet::client {
namespace {

constexpr int kBarWidth = 40;

std::string distance_text(const WatchPoint& p, const std::string& key) {
  const auto it = p.distances.find(key);
  return it == p.distances.end() ? "-" : rounded_number(it->second, 5);
}

std::string title(const WatchState& s) {
  std::string t = "fnet watch  run " + (s.run.empty() ? std::string("(newest)") : s.run);
  if (s.complete) t += " \u2014 complete";
  return t + "   (Ctrl-C to leave)";
}

void density_line(std::ostream& out, const WatchState& s, double rho) {
  out << "rho " << std::fixed << std::setprecision(4) << rho;
  if (s.rho_start && s.rho_end && *s.rho_end > *s.rho_start) {
    const double fraction = (rho - *s.rho_start) / (*s.rho_end - *s.rho_start);
    const int filled = std::clamp(static_cast<int>(std::lround(kBarWidth * fraction)), 0, kBarWidth);
    out << " [" << std::string(filled, '#') << std::string(kBarWidth - filled, '.') << "] " << *s.rho_end;
  }
  out << std::defaultfloat << "\n";
}

void distances_table(std::ostream& out, const WatchPoint& p) {
  out << std::left << std::setw(26)
      << ("distance from frame " + (p.previous ? std::to_string(*p.previous) : std::string("-"))) << std::right;
  for (const ForceKind force : kForces)
    for (int dim = 0; dim < 2; ++dim)
      out << std::setw(16) << (std::string(to_string(force)) + " PD" + std::to_string(dim));
  out << "\n";
  for (const Metric metric : kMetrics) {
    out << std::left << std::setw(26) << to_string(metric) << std::right;
    for (const ForceKind force : kForces)
      for (int dim = 0; dim < 2; ++dim) out << std::setw(16) << distance_text(p, series_key(metric, dim, force));
    out << "\n";
  }
}

void trend_line(std::ostream& out, const WatchState& s) {
  out << s.trend_key << ", last " << s.trend.size() << (s.trend.size() == 1 ? " frame:" : " frames:");
  if (s.trend.empty()) {
    out << " none yet\n";
    return;
  }
  const auto [lo, hi] = std::minmax_element(s.trend.begin(), s.trend.end());
  out << "  min " << rounded_number(*lo, 4) << " " << sparkline(s.trend) << " max " << rounded_number(*hi, 4) << "\n";
}

}  // namespace

WatchPoint watch_point_from_json(const nlohmann::json& params) {
  WatchPoint p;
  p.frame = params.at("frame").get<std::uint32_t>();
  p.step = params.at("step").get<std::uint64_t>();
  p.time = params.at("time").get<double>();
  p.rho = params.at("rho").get<double>();
  p.z = params.at("z").get<double>();
  if (!params.at("previous").is_null()) p.previous = params.at("previous").get<std::uint32_t>();
  for (const auto& [key, value] : params.at("distances").items())
    if (!value.is_null()) p.distances[key] = value.get<double>();
  return p;
}

void WatchState::add(const WatchPoint& point) {
  if (!rho_start) rho_start = point.rho;
  if (const auto it = point.distances.find(trend_key); it != point.distances.end()) {
    trend.push_back(it->second);
    if (trend.size() > kTrendLength) trend.pop_front();
  }
  if (planned_frames && point.frame + 1 >= *planned_frames) complete = true;
  last = point;
}

std::string frame_count(const WatchState& state) {
  std::string out = "frames " + std::to_string(state.last ? state.last->frame + 1 : 0);
  if (state.planned_frames) out.append("/").append(std::to_string(*state.planned_frames));
  return out;
}

std::string render_watch_screen(const WatchState& s) {
  std::ostringstream out;
  out << title(s) << "\n\n";
  if (!s.status.empty()) out << s.status << "\n\n";
  if (!s.last) return out.str();
  const WatchPoint& p = *s.last;
  out << frame_count(s) << "   frame " << p.frame << "   step " << p.step << "   time " << rounded_number(p.time, 6)
      << "\n";
  density_line(out, s, p.rho);
  out << "Z   " << std::fixed << std::setprecision(3) << p.z << std::defaultfloat << "\n\n";
  distances_table(out, p);
  out << "\n";
  trend_line(out, s);
  return out.str();
}

std::string render_watch_line(const WatchState& s) {
  if (!s.last) return s.status;
  const WatchPoint& p = *s.last;
  std::ostringstream out;
  out << "frame " << p.frame << " (" << frame_count(s) << ") rho " << rounded_number(p.rho, 6) << " Z "
      << rounded_number(p.z, 4) << " " << s.trend_key << " " << distance_text(p, s.trend_key);
  if (s.complete) out << " complete";
  return out.str();
}

std::string sparkline(const std::deque<double>& values) {
  static const char* kBars[] = {"\u2581", "\u2582", "\u2583", "\u2584", "\u2585", "\u2586", "\u2587", "\u2588"};
  if (values.empty()) return "";
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  std::string out;
  for (const double v : values) {
    const int k = *hi > *lo ? static_cast<int>(std::lround(7.0 * (v - *lo) / (*hi - *lo))) : 0;
    out += kBars[std::clamp(k, 0, 7)];
  }
  return out;
}

}  // namespace fnet::client
