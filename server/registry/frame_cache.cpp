#include "server/registry/frame_cache.hpp"

namespace fnet::server {
namespace {

// An entry's own bookkeeping: its list node and map node (each with a copy of the key), and
// the shared value's control block, over the key's run name counted twice.
constexpr std::size_t kEntryOverhead = 2 * sizeof(void*) * 4 + 2 * (sizeof(std::string) + 16) + 32;

std::size_t diagram_bytes(const FrameDiagrams& d) {
  return (d.pd0.capacity() + d.pd1.capacity()) * sizeof(PersistencePoint);
}

}  // namespace

std::size_t held_bytes(const AnalyzedFrame& frame) {
  return sizeof(AnalyzedFrame) + frame.header.run_id.capacity() + diagram_bytes(frame.diagrams.normal) +
         diagram_bytes(frame.diagrams.tangential) + (frame.network ? held_bytes(*frame.network) : 0);
}

std::size_t held_bytes(const Frame& network) {
  return sizeof(Frame) + network.label.capacity() + network.particles.capacity() * sizeof(Particle) +
         network.contacts.capacity() * sizeof(Contact);
}

const FrameCache::Value* FrameCache::find(Key key) {
  const auto it = index_.find(key);
  if (it == index_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  order_.splice(order_.begin(), order_, it->second);
  return &it->second->value;
}

std::shared_ptr<const AnalyzedFrame> FrameCache::diagrams(const std::string& run, std::uint32_t index) {
  std::lock_guard lock(mutex_);
  const Value* v = find({run, index, Kind::diagrams});
  return v ? std::get<std::shared_ptr<const AnalyzedFrame>>(*v) : nullptr;
}

std::shared_ptr<const Frame> FrameCache::network(const std::string& run, std::uint32_t index) {
  std::lock_guard lock(mutex_);
  const Value* v = find({run, index, Kind::network});
  return v ? std::get<std::shared_ptr<const Frame>>(*v) : nullptr;
}

void FrameCache::insert(Key key, Value value, std::size_t bytes) {
  bytes += kEntryOverhead + 2 * std::get<0>(key).capacity();
  std::lock_guard lock(mutex_);
  if (const auto it = index_.find(key); it != index_.end()) {
    bytes_ -= it->second->bytes;
    order_.erase(it->second);
    index_.erase(it);
  }
  if (bytes > capacity_) return;
  while (bytes_ + bytes > capacity_) {
    bytes_ -= order_.back().bytes;
    index_.erase(order_.back().key);
    order_.pop_back();
  }
  order_.push_front({key, std::move(value), bytes});
  index_.emplace(std::move(key), order_.begin());
  bytes_ += bytes;
}

void FrameCache::keep(const std::string& run, std::uint32_t index, std::shared_ptr<const AnalyzedFrame> frame) {
  const std::size_t bytes = held_bytes(*frame);
  insert({run, index, Kind::diagrams}, std::move(frame), bytes);
}

void FrameCache::keep(const std::string& run, std::uint32_t index, std::shared_ptr<const Frame> network) {
  const std::size_t bytes = held_bytes(*network);
  insert({run, index, Kind::network}, std::move(network), bytes);
}

FrameCacheStats FrameCache::stats() const {
  std::lock_guard lock(mutex_);
  return {capacity_, bytes_, order_.size(), hits_, misses_};
}

}  // namespace fnet::server
