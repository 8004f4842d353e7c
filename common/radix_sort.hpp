// Stable LSD radix sort of records by a 64-bit unsigned key, for the large sorts on the hot path
// (edges by force value). Digits shared by every key are skipped, so typical force data costs
// 5-7 passes; small inputs fall back to std::stable_sort.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fnet {

// Sorts `items` ascending by key(item), keeping the input order among equal keys.
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

}  // namespace fnet
