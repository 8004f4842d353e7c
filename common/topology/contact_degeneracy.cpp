#include "common/topology/contact_degeneracy.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fnet {

// Matula and Beck's peeling: grains in buckets by their degree among the grains not yet taken;
// take one of least degree, lower its neighbours' degrees. The bucket array is laid out as one
// vector sorted by degree (order), with the start of each degree's bucket (start) and each
// grain's place in it (place), so that moving a grain down one bucket is a swap.
std::size_t contact_degeneracy(const Frame& frame) {
  const std::size_t n = frame.particle_count;
  if (n == 0 || frame.contacts.empty()) return 0;
  std::vector<std::uint32_t> degree(n, 0), neighbours(2 * frame.contacts.size());
  std::vector<std::size_t> offset(n + 1, 0);
  for (const Contact& c : frame.contacts) ++degree[c.i], ++degree[c.j];
  for (std::size_t v = 0; v < n; ++v) offset[v + 1] = offset[v] + degree[v];
  {
    std::vector<std::size_t> fill(offset.begin(), offset.end() - 1);
    for (const Contact& c : frame.contacts) {
      neighbours[fill[c.i]++] = static_cast<std::uint32_t>(c.j);
      neighbours[fill[c.j]++] = static_cast<std::uint32_t>(c.i);
    }
  }
  const std::uint32_t max_degree = *std::max_element(degree.begin(), degree.end());
  std::vector<std::uint32_t> start(max_degree + 2, 0), order(n), place(n);
  for (std::size_t v = 0; v < n; ++v) ++start[degree[v] + 1];
  for (std::size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t v = 0; v < n; ++v) {
      place[v] = fill[degree[v]]++;
      order[place[v]] = static_cast<std::uint32_t>(v);
    }
  }
  std::size_t k = 0;
  for (std::size_t at = 0; at < n; ++at) {
    const std::uint32_t v = order[at];  // least degree among the grains not yet taken
    k = std::max<std::size_t>(k, degree[v]);
    for (std::size_t e = offset[v]; e < offset[v + 1]; ++e) {
      const std::uint32_t u = neighbours[e];
      if (place[u] <= at || degree[u] <= degree[v]) continue;  // taken, or no lower than v
      // u moves to the front of its bucket, then into the bucket below.
      const std::uint32_t front = std::max<std::uint32_t>(start[degree[u]], static_cast<std::uint32_t>(at + 1));
      const std::uint32_t w = order[front];
      std::swap(order[front], order[place[u]]);
      place[w] = place[u];
      place[u] = front;
      start[degree[u]] = front + 1;
      --degree[u];
    }
  }
  return k;
}

}  // namespace fnet
