#include "client/fnetctl/watch_view.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "client/fnetctl/value_text.hpp"
#include "common/analysis/metric_vocabulary.hpp"

namespace fnet::client {
namespace {

constexpr int kBarWidth = 40;
constexpr int kLabelWidth = 26;
constexpr int kValueWidth = 12;
// Frames a simulation publishes come seconds apart; gaps below this are a replay of stored frames.
constexpr double kLiveGap = 0.01;

std::string distance_text(const WatchPoint& p, const std::string& key) {
  const auto it = p.distances.find(key);
  return it == p.distances.end() ? "-" : rounded_number(it->second, 5);
}

// "bottleneck/pd1/tangential" -> "bottleneck PD1 tangential".
std::string series_label(const std::string& key) {
  std::string out = key;
  std::replace(out.begin(), out.end(), '/', ' ');
  if (const auto pd = out.find(" pd"); pd != std::string::npos) out.replace(pd + 1, 2, "PD");
  return out;
}

std::string title(const WatchState& s) {
  std::string t = "fnet watch  run " + (s.run.empty() ? std::string("(newest)") : s.run);
  if (s.complete) t += " \u2014 complete";
  return t + "   (Ctrl-C to leave)";
}

void frame_line(std::ostream& out, const WatchState& s, const WatchPoint& p) {
  out << frame_count(s) << "   frame " << p.frame << "   step " << p.step << "   time " << rounded_number(p.time, 6)
      << " tau_c";
  if (const auto eta = s.eta_seconds()) out << "   ETA " << duration_text(*eta);
  if (s.server_in_flight)
    out << "   server lag " << *s.server_in_flight << " frame" << (*s.server_in_flight == 1 ? "" : "s") << " ("
        << std::fixed << std::setprecision(2) << s.server_oldest_pending.value_or(0) << std::defaultfloat << " s)";
  out << "\n";
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

void contact_line(std::ostream& out, const WatchState& s, double z) {
  out << "Z   " << std::fixed << std::setprecision(3) << z << std::defaultfloat << "   ";
  if (s.rho_j)
    out << "rho_J " << std::fixed << std::setprecision(4) << *s.rho_j << std::defaultfloat << " (Z first reached 3)";
  else
    out << "rho_J not yet (Z has not reached 3)";
  out << "\n";
}

// The column of the first frame in the window at or past rho_J, if it lies in the window and
// an earlier frame of the window lies before it.
std::optional<std::size_t> jamming_column(const WatchState& s) {
  if (!s.rho_j) return std::nullopt;
  for (std::size_t k = 0; k < s.history.size(); ++k)
    if (s.history[k].rho >= *s.rho_j) return k == 0 ? std::nullopt : std::optional(k);
  return std::nullopt;
}

void series_rows(std::ostream& out, const WatchState& s, const WatchPoint& p) {
  out << std::left << std::setw(kLabelWidth)
      << ("distance from frame " + (p.previous ? std::to_string(*p.previous) : std::string("-"))) << std::right
      << std::setw(kValueWidth) << "latest"
      << "  last " << s.history.size() << (s.history.size() == 1 ? " frame" : " frames")
      << ", log scale (\u00b7: 0)   min / max\n";
  for (const std::string& key : s.keys) {
    std::vector<std::optional<double>> values;
    std::optional<double> lo, hi;
    for (const WatchPoint& h : s.history) {
      const auto it = h.distances.find(key);
      values.push_back(it == h.distances.end() ? std::nullopt : std::optional(it->second));
      if (it != h.distances.end()) {
        lo = std::min(lo.value_or(it->second), it->second);
        hi = std::max(hi.value_or(it->second), it->second);
      }
    }
    const std::string line = log_sparkline(values);
    out << std::left << std::setw(kLabelWidth) << series_label(key) << std::right << std::setw(kValueWidth)
        << distance_text(p, key) << "  " << line << std::string(kTrendLength - values.size() + 2, ' ')
        << (lo ? "min " + rounded_number(*lo, 4) + " / max " + rounded_number(*hi, 4) : std::string("-")) << "\n";
  }
  if (const auto column = jamming_column(s))
    out << std::string(kLabelWidth + kValueWidth + 2 + *column, ' ') << "^ rho_J (frame " << s.history[*column].frame
        << ")\n";
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

std::vector<std::string> all_series_keys() {
  std::vector<std::string> keys;
  for (const Metric metric : kMetrics)
    for (const ForceKind force : kForces)
      for (int dim = 0; dim < 2; ++dim) keys.push_back(series_key(metric, dim, force));
  return keys;
}

void WatchState::add(const WatchPoint& point, double arrived) {
  if (!rho_start) rho_start = point.rho;
  history.push_back(point);
  if (history.size() > kTrendLength) history.pop_front();
  arrivals.push_back(arrived);
  if (arrivals.size() > kRateWindow) arrivals.pop_front();
  if (planned_frames && point.frame + 1 >= *planned_frames) complete = true;
  last = point;
}

std::optional<double> WatchState::eta_seconds() const {
  if (!planned_frames || !last || complete || arrivals.size() < 3) return std::nullopt;
  std::vector<double> gaps;
  for (std::size_t k = 1; k < arrivals.size(); ++k) gaps.push_back(arrivals[k] - arrivals[k - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  const double gap = gaps[gaps.size() / 2];
  if (!(gap >= kLiveGap)) return std::nullopt;  // a replay, not the simulation's pace
  const double remaining = *planned_frames > last->frame + 1 ? *planned_frames - (last->frame + 1) : 0;
  return remaining * gap;
}

std::string frame_count(const WatchState& state) {
  std::string out = "frames " + std::to_string(state.last ? state.last->frame + 1 : 0);
  if (state.planned_frames) out.append("/").append(std::to_string(*state.planned_frames));
  return out;
}

std::string render_watch_screen(const WatchState& s) {
  std::ostringstream out;
  out << title(s) << "\n";
  if (!s.setting.empty()) out << s.setting << "\n";
  out << "\n";
  if (!s.status.empty()) out << s.status << "\n\n";
  if (!s.last) return out.str();
  const WatchPoint& p = *s.last;
  frame_line(out, s, p);
  density_line(out, s, p.rho);
  contact_line(out, s, p.z);
  out << "\n";
  series_rows(out, s, p);
  return out.str();
}

std::string render_watch_line(const WatchState& s) {
  if (!s.last) return s.status;
  const WatchPoint& p = *s.last;
  std::ostringstream out;
  out << "frame " << p.frame << " (" << frame_count(s) << ") rho " << rounded_number(p.rho, 6) << " Z "
      << rounded_number(p.z, 4) << " " << s.trend_key << " " << distance_text(p, s.trend_key);
  if (s.rho_j && p.rho >= *s.rho_j) out << " (past rho_J " << rounded_number(*s.rho_j, 5) << ")";
  if (s.complete) out << " complete";
  return out.str();
}

std::string log_sparkline(const std::vector<std::optional<double>>& values) {
  static const char* kBars[] = {"\u2581", "\u2582", "\u2583", "\u2584", "\u2585", "\u2586", "\u2587", "\u2588"};
  std::optional<double> lo, hi;
  for (const auto& v : values)
    if (v && *v > 0 && std::isfinite(*v)) {
      lo = std::min(lo.value_or(std::log10(*v)), std::log10(*v));
      hi = std::max(hi.value_or(std::log10(*v)), std::log10(*v));
    }
  std::string out;
  for (const auto& v : values) {
    if (!v) {
      out += ' ';
    } else if (!(*v > 0)) {
      out += "\u00b7";
    } else if (!std::isfinite(*v)) {
      out += kBars[7];
    } else {
      const double x = std::log10(*v);
      const int k = *hi > *lo ? static_cast<int>(std::lround(7.0 * (x - *lo) / (*hi - *lo))) : 0;
      out += kBars[std::clamp(k, 0, 7)];
    }
  }
  return out;
}

std::string duration_text(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  const long h = total / 3600, m = total % 3600 / 60, s = total % 60;
  std::ostringstream out;
  out << std::setfill('0');
  if (h > 0)
    out << h << "h" << std::setw(2) << m << "m";
  else if (m > 0)
    out << m << "m" << std::setw(2) << s << "s";
  else
    out << s << "s";
  return out.str();
}

}  // namespace fnet::client
