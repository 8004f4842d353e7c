// Radix sorts for the hot path: a stable LSD sort of records by a 64-bit key, and a sort of
// (key, tie) pairs that orders edges by force value with a total, input-independent tie order.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

namespace fnet {

// Sorts `items` ascending by key(item), keeping the input order among equal keys. Digits shared
// by every key are skipped; small inputs fall back to std::stable_sort.
template <class T, class KeyFn>
void radix_sort(std::vector<T>& items, KeyFn key) {
  const std::size_t n = items.size();
  if (n < 256) {
    std::stable_sort(items.begin(), items.end(), [&](const T& a, const T& b) { return key(a) < key(b); });
    return;
  }
  std::vector<std::uint64_t> keys(n);
  std::uint64_t all_and = ~std::uint64_t{0}, all_or = 0;
  for (std::size_t k = 0; k < n; ++k) {
    keys[k] = key(items[k]);
    all_and &= keys[k];
    all_or |= keys[k];
  }
  const std::uint64_t varying = all_and ^ all_or;
  std::vector<T> items_tmp(n);
  std::vector<std::uint64_t> keys_tmp(n);
  for (int shift = 0; shift < 64; shift += 8) {
    if (((varying >> shift) & 0xff) == 0) continue;
    std::array<std::size_t, 257> offset{};
    for (std::size_t k = 0; k < n; ++k) ++offset[((keys[k] >> shift) & 0xff) + 1];
    for (std::size_t b = 0; b < 256; ++b) offset[b + 1] += offset[b];
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t dst = offset[(keys[k] >> shift) & 0xff]++;
      items_tmp[dst] = items[k];
      keys_tmp[dst] = keys[k];
    }
    items.swap(items_tmp);
    keys.swap(keys_tmp);
  }
}

// No member initializers: buffers of these are allocated uninitialized on the hot path.
struct KeyedRecord {
  std::uint64_t key, tie;
};

namespace detail {

inline bool keyed_less(const KeyedRecord& a, const KeyedRecord& b) {
  return a.key != b.key ? a.key < b.key : a.tie < b.tie;
}

// Buckets up to this size are finished by insertion sort.
inline constexpr std::size_t kInsertionRun = 24;

inline void insertion_sort(KeyedRecord* a, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i) {
    const KeyedRecord x = a[i];
    std::size_t j = i;
    for (; j > 0 && keyed_less(x, a[j - 1]); --j) a[j] = a[j - 1];
    a[j] = x;
  }
}

// One MSD level, for a crowd of records whose keys the LSD passes could not tell apart: the
// range [lo, hi] of their keys is cut into about as many buckets as there are records (at most
// 2^MaxBits), and crowded buckets take another level. Whatever the distribution, each level
// narrows the range, so no input makes this quadratic. Scatters a[0, n) into out; end[b] is
// then the end of bucket b. Returns the bucket count.
template <int MaxBits>
std::size_t scatter(const KeyedRecord* a, KeyedRecord* out, std::size_t n, std::uint64_t lo, std::uint64_t hi,
                    std::uint32_t* end) {
  const int width = static_cast<int>(std::bit_width(hi - lo));
  const int bits = std::min(std::clamp(static_cast<int>(std::bit_width(n)), 4, MaxBits), width);
  const int shift = width - bits;
  const std::size_t buckets = std::size_t{1} << bits;
  std::fill(end, end + buckets, 0u);  // counts, then starts, then (after the scatter) ends
  for (std::size_t i = 0; i < n; ++i) ++end[(a[i].key - lo) >> shift];
  std::uint32_t sum = 0;
  for (std::size_t b = 0; b < buckets; ++b) sum += std::exchange(end[b], sum);
  for (std::size_t i = 0; i < n; ++i) out[end[(a[i].key - lo) >> shift]++] = a[i];
  return buckets;
}

inline void sort_ties(KeyedRecord* a, std::size_t n) {
  std::sort(a, a + n, [](const KeyedRecord& x, const KeyedRecord& y) { return x.tie < y.tie; });
}

// A crowd sorted in place (tmp as scratch): small buckets by insertion, larger ones recursively.
inline void sort_crowd(KeyedRecord* a, KeyedRecord* tmp, std::size_t n) {
  if (n <= kInsertionRun) return insertion_sort(a, n);
  std::uint64_t lo = a[0].key, hi = a[0].key;
  for (std::size_t i = 1; i < n; ++i) lo = std::min(lo, a[i].key), hi = std::max(hi, a[i].key);
  if (lo == hi) return sort_ties(a, n);
  std::uint32_t end[1 << 11];
  const std::size_t buckets = scatter<11>(a, tmp, n, lo, hi, end);
  std::memcpy(static_cast<void*>(a), tmp, n * sizeof(KeyedRecord));
  for (std::size_t b = 0, first = 0; b < buckets; first = end[b++])
    if (end[b] - first > 1) sort_crowd(a + first, tmp + first, end[b] - first);
}

// LSD radix on the top bits of key - lo, about ten bits finer than there are records, in Passes
// stable passes of 11 bits with all counts taken in one pass. Records then differ in those bits
// but for rare crowds, which one more pass finds and sorts; the branch that finds them is
// predictable, unlike sorting every small bucket. Returns whichever buffer holds the result.
template <int Passes>
std::span<KeyedRecord> sort_lsd(std::span<KeyedRecord> items, std::span<KeyedRecord> scratch, std::uint64_t lo,
                                int width) {
  constexpr int digit = 11;
  constexpr std::uint64_t mask = (std::uint64_t{1} << digit) - 1;
  const int shift = std::max(0, width - digit * Passes);
  std::uint32_t start[Passes][1 << digit] = {};
  for (const KeyedRecord& r : items) {
    const std::uint64_t d = (r.key - lo) >> shift;
    for (int p = 0; p < Passes; ++p) ++start[p][(d >> (p * digit)) & mask];
  }
  for (auto& counts : start) {
    std::uint32_t sum = 0;
    for (std::size_t b = 0; b <= mask; ++b) sum += std::exchange(counts[b], sum);
  }
  std::span<KeyedRecord> from = items, to = scratch.first(items.size());
  for (int p = 0; p < Passes; ++p) {
    const int at = shift + p * digit;
    for (const KeyedRecord& r : from) to[start[p][((r.key - lo) >> at) & mask]++] = r;
    std::swap(from, to);
  }
  const std::size_t n = from.size();
  const auto sorted_bits = [&](std::size_t i) { return (from[i].key - lo) >> shift; };
  for (std::size_t i = 0, j = 0; i < n; i = j) {
    for (j = i + 1; j < n && sorted_bits(j) == sorted_bits(i);) ++j;
    if (j - i > 1) [[unlikely]]
      sort_crowd(&from[i], &to[i], j - i);
  }
  return from;
}

inline std::span<KeyedRecord> sort_lsd(std::span<KeyedRecord> items, std::span<KeyedRecord> scratch, std::uint64_t lo,
                                       std::uint64_t hi) {
  const int width = static_cast<int>(std::bit_width(hi - lo));
  const int bits = std::min(width, static_cast<int>(std::bit_width(items.size())) + 10);
  if (bits <= 22) return sort_lsd<2>(items, scratch, lo, width);
  if (bits <= 33) return sort_lsd<3>(items, scratch, lo, width);
  return sort_lsd<4>(items, scratch, lo, width);
}

}  // namespace detail

// Sorts `items` ascending by (key, tie), given the least and greatest key. `scratch` must be at
// least as long as `items`. Returns the sorted records: `items` itself, or the front of
// `scratch`, whichever saves a copy. Requires items.size() < 2^32.
inline std::span<KeyedRecord> sort_keyed(std::span<KeyedRecord> items, std::span<KeyedRecord> scratch, std::uint64_t lo,
                                         std::uint64_t hi) {
  if (lo == hi) {
    detail::sort_ties(items.data(), items.size());
    return items;
  }
  if (items.size() <= detail::kInsertionRun) {
    detail::insertion_sort(items.data(), items.size());
    return items;
  }
  return detail::sort_lsd(items, scratch, lo, hi);
}

}  // namespace fnet
