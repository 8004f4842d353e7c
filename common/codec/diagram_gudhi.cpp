#include "common/codec/diagram_gudhi.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fnet {

namespace {

void append_number(std::string& out, double v) {
  if (std::isinf(v)) {
    out += v > 0 ? "inf" : "-inf";
    return;
  }
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  out.append(buffer.data(), result.ptr);
}

}  // namespace

GudhiEssential parse_gudhi_essential(const std::string& name) {
  if (name == "inf") return GudhiEssential::inf;
  if (name == "floor") return GudhiEssential::floor;
  throw std::invalid_argument("unknown convention '" + name + "' (expected inf or floor)");
}

Diagram gudhi_diagram(const Diagram& diagram, GudhiEssential essential) {
  Diagram out;
  out.reserve(diagram.size());
  for (const PersistencePoint& p : diagram) {
    // 0.0 - x rather than -x: a birth or death of 0 stays +0, which reads as "0", not "-0".
    const double birth = 0.0 - p.birth;
    if (p.death != kNeverDies) {
      out.push_back({birth, 0.0 - p.death});
    } else if (essential == GudhiEssential::inf) {
      out.push_back({birth, std::numeric_limits<double>::infinity()});
    } else if (birth != 0.0) {
      out.push_back({birth, 0.0});
    }
  }
  return out;
}

std::string diagram_gudhi_text(const FrameDiagrams& diagrams, GudhiEssential essential) {
  std::string out = essential == GudhiEssential::inf
                        ? "# fnet diagrams, sublevel form: dim birth death = 0|1 -b -d; never dies: inf\n"
                        : "# fnet diagrams, sublevel form: dim birth death = 0|1 -b -d; never dies: 0 (floor)\n";
  const std::array<const Diagram*, 2> by_dim{&diagrams.pd0, &diagrams.pd1};
  for (std::size_t dim = 0; dim < by_dim.size(); ++dim) {
    for (const PersistencePoint& p : gudhi_diagram(*by_dim[dim], essential)) {
      out += dim == 0 ? "0 " : "1 ";
      append_number(out, p.birth);
      out += ' ';
      append_number(out, p.death);
      out += '\n';
    }
  }
  return out;
}

}  // namespace fnet
