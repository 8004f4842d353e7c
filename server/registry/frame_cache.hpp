// What fnet-server reads back from the runs' stores, kept for the next request: each committed
// frame with its diagrams, and force networks, least recently used dropped first, in one cache
// every run shares. Its bound is in bytes, the heap the entries hold (their vectors' capacities,
// strings, and the cache's own bookkeeping per entry): the entries it holds never sum past it, and
// an entry larger than the bound is handed back without being kept. Thread-safe; an entry handed
// out stays valid after it is dropped (shared ownership), so what callers hold is theirs to count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <variant>

#include "common/analysis/analyzed_frame.hpp"
#include "common/topology/frame.hpp"

namespace fnet::server {

struct FrameCacheStats {
  std::size_t capacity_bytes = 0, bytes = 0, entries = 0;
  std::uint64_t hits = 0, misses = 0;
};

// The heap bytes a value holds, as the cache counts them.
std::size_t held_bytes(const AnalyzedFrame& frame);
std::size_t held_bytes(const Frame& network);

class FrameCache {
 public:
  explicit FrameCache(std::size_t capacity_bytes) : capacity_(capacity_bytes) {}
  FrameCache(const FrameCache&) = delete;
  FrameCache& operator=(const FrameCache&) = delete;

  // The entry of frame `index` of `run`, or null (a miss); a hit makes it the most recently used.
  std::shared_ptr<const AnalyzedFrame> diagrams(const std::string& run, std::uint32_t index);
  std::shared_ptr<const Frame> network(const std::string& run, std::uint32_t index);
  // Keeps `value` as the most recently used entry (replacing one of the same key), then drops the
  // least recently used until the bound holds.
  void keep(const std::string& run, std::uint32_t index, std::shared_ptr<const AnalyzedFrame> frame);
  void keep(const std::string& run, std::uint32_t index, std::shared_ptr<const Frame> network);

  FrameCacheStats stats() const;

 private:
  enum class Kind { diagrams, network };
  using Key = std::tuple<std::string, std::uint32_t, Kind>;
  using Value = std::variant<std::shared_ptr<const AnalyzedFrame>, std::shared_ptr<const Frame>>;
  struct Entry {
    Key key;
    Value value;
    std::size_t bytes = 0;
  };
  using Order = std::list<Entry>;  // most recently used first

  const Value* find(Key key);
  void insert(Key key, Value value, std::size_t bytes);

  const std::size_t capacity_;
  mutable std::mutex mutex_;
  Order order_;
  std::map<Key, Order::iterator> index_;
  std::size_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace fnet::server
