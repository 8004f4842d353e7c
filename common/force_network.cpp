#include "common/force_network.hpp"

#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/radix_sort.hpp"

namespace fnet {

std::string_view to_string(ForceKind kind) { return kind == ForceKind::normal ? "normal" : "tangential"; }

ForceKind parse_force_kind(std::string_view text) {
  if (text == "normal") return ForceKind::normal;
  if (text == "tangential") return ForceKind::tangential;
  throw std::invalid_argument("unknown force '" + std::string(text) + "' (expected normal or tangential)");
}

ForceNetwork build_network(const Frame& frame, ForceKind kind) {
  ForceNetwork net;
  net.vertex_count = frame.particle_count;
  net.edges.reserve(frame.contacts.size());
  for (const Contact& c : frame.contacts) {
    const double force = std::fabs(kind == ForceKind::normal ? c.fn : c.ft);
    if (!(force > 0)) continue;
    const auto a = static_cast<std::uint32_t>(c.i), b = static_cast<std::uint32_t>(c.j);
    net.edges.push_back({std::min(a, b), std::max(a, b), force});
  }
  if (net.edges.empty()) return net;

  // For positive doubles the bit pattern orders like the value; its complement sorts descending.
  radix_sort(net.edges, [](const Edge& e) { return ~std::bit_cast<std::uint64_t>(e.value); });

  // Summing in sorted order (smallest first, extended precision) makes the mean, and so every
  // normalized value, independent of the order of the input rows.
  long double sum = 0;
  for (auto it = net.edges.rbegin(); it != net.edges.rend(); ++it) sum += it->value;
  net.mean_force = static_cast<double>(sum / static_cast<long double>(net.edges.size()));
  for (Edge& e : net.edges) e.value /= net.mean_force;
  return net;
}

}  // namespace fnet
