#include "common/topology/force_network.hpp"

#include <bit>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "common/topology/huge_pages.hpp"
#include "common/topology/radix_sort.hpp"

namespace fnet {
namespace {

// Uninitialized records kept by each thread between calls: a service analyses frame after frame
// of similar size, and fresh memory costs a page fault per page on every call. Reallocated when
// too small, and also when more than four times too large, so that one huge frame does not pin
// its memory for good.
class SortBuffer {
 public:
  std::span<KeyedRecord> get(std::size_t n) {
    if (n > capacity_ || 4 * n < capacity_) {
      data_.reset();
      data_ = std::make_unique_for_overwrite<KeyedRecord[]>(n);
      capacity_ = n;
      prefer_huge_pages(data_.get(), n * sizeof(KeyedRecord));
    }
    return {data_.get(), n};
  }

 private:
  std::unique_ptr<KeyedRecord[]> data_;
  std::size_t capacity_ = 0;
};

}  // namespace

std::string_view to_string(ForceKind kind) { return kind == ForceKind::normal ? "normal" : "tangential"; }

ForceKind parse_force_kind(std::string_view text) {
  if (text == "normal") return ForceKind::normal;
  if (text == "tangential") return ForceKind::tangential;
  throw std::invalid_argument("unknown force '" + std::string(text) + "' (expected normal or tangential)");
}

ForceNetwork build_network(const Frame& frame, ForceKind kind) {
  thread_local SortBuffer items_buffer, scratch_buffer;
  ForceNetwork net;
  net.vertex_count = frame.particle_count;
  const double Contact::*field = kind == ForceKind::normal ? &Contact::fn : &Contact::ft;

  // For positive doubles the bit pattern orders like the value; its complement sorts descending.
  // Ties go by the endpoints, so the order never depends on the order of the input rows.
  const std::span<KeyedRecord> all = items_buffer.get(frame.contacts.size());
  std::size_t n = 0;
  std::uint64_t lo = ~std::uint64_t{0}, hi = 0;
  for (const Contact& c : frame.contacts) {
    const double force = std::fabs(c.*field);
    if (!(force > 0)) continue;
    auto i = static_cast<std::uint64_t>(c.i), j = static_cast<std::uint64_t>(c.j);
    const std::uint64_t swap = (i ^ j) & (std::uint64_t{0} - (j < i));  // rows list pairs either way:
    i ^= swap, j ^= swap;                                               // no branch to mispredict
    const std::uint64_t key = ~std::bit_cast<std::uint64_t>(force);
    lo = std::min(lo, key), hi = std::max(hi, key);
    all[n++] = {key, i << 32 | j};
  }
  if (n == 0) return net;
  const std::span<const KeyedRecord> items = sort_keyed(all.first(n), scratch_buffer.get(n), lo, hi);

  // Summing in sorted order (smallest first, extended precision) makes the mean, and so every
  // normalized value, independent of the order of the input rows. Four interleaved sums, added
  // up in a fixed order, keep the additions off one long dependency chain.
  long double part[4] = {0, 0, 0, 0};
  std::size_t k = n;
  for (; k >= 4; k -= 4)
    for (std::size_t j = 0; j < 4; ++j) part[j] += std::bit_cast<double>(~items[k - 1 - j].key);
  for (; k > 0; --k) part[0] += std::bit_cast<double>(~items[k - 1].key);
  const long double sum = (part[0] + part[1]) + (part[2] + part[3]);
  net.mean_force = static_cast<double>(sum / static_cast<long double>(n));
  net.edges.reserve(n);
  prefer_huge_pages(net.edges.data(), n * sizeof(Edge));
  net.edges.resize(n);
  Edge* out = net.edges.data();
  const double mean = net.mean_force;
  for (std::size_t e = 0; e < n; ++e)
    out[e] = {static_cast<std::uint32_t>(items[e].tie >> 32), static_cast<std::uint32_t>(items[e].tie),
              std::bit_cast<double>(~items[e].key) / mean};
  return net;
}

}  // namespace fnet
