#include "common/run/frame_bounds.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "common/topology/frame.hpp"

namespace fnet {
namespace {

// The shortest text that reads back as v.
std::string number(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

// Empty when v is finite and in [lo, hi].
std::string range_problem(const char* name, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return {};
  return std::string(name) + " = " + number(v) + " is not a finite number in [" + number(lo) + ", " + number(hi) + "]";
}

}  // namespace

std::string header_problem(const FrameHeader& h) {
  std::string problem = range_problem("rho", h.rho, 0, kMaxRho);
  if (problem.empty()) problem = range_problem("z", h.z, 0, kMaxZ);
  if (problem.empty() && !(std::isfinite(h.time) && h.time >= 0))
    problem = "time = " + number(h.time) + " is not a finite number >= 0";
  if (problem.empty() && h.step > kMaxStep)
    problem = "step = " + std::to_string(h.step) + " exceeds 2^53, the largest integer every JSON reader holds exactly";
  return problem;
}

std::size_t frame_bytes(std::size_t grains, std::size_t contacts, std::size_t wall_contacts) {
  return grains * sizeof(Particle) + contacts * sizeof(Contact) + wall_contacts * sizeof(WallContact);
}

std::string mebibytes(std::size_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << static_cast<double>(bytes) / (1 << 20) << " MiB";
  return s.str();
}

}  // namespace fnet
