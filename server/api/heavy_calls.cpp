#include "server/api/heavy_calls.hpp"

#include <utility>

namespace fnet::server {

HeavyCalls::HeavyCalls(Offload offload, std::size_t per_connection)
    : offload_(std::move(offload)), per_connection_(per_connection == 0 ? 1 : per_connection) {}

void HeavyCalls::submit(std::uint64_t connection, std::function<void()> work) {
  {
    std::lock_guard lock(mutex_);
    Queue& q = queues_[connection];
    if (q.running >= per_connection_) {
      q.waiting.push_back(std::move(work));
      ++waiting_;
      return;
    }
    ++q.running;
  }
  start(connection, std::move(work));
}

std::size_t HeavyCalls::waiting() const {
  std::lock_guard lock(mutex_);
  return waiting_;
}

void HeavyCalls::start(std::uint64_t connection, std::function<void()> work) {
  offload_([self = shared_from_this(), connection, work = std::move(work)] {
    work();  // ends its call whatever happens (make_api catches)
    self->ended(connection);
  });
}

void HeavyCalls::ended(std::uint64_t connection) {
  std::function<void()> next;
  {
    std::lock_guard lock(mutex_);
    const auto it = queues_.find(connection);
    if (it == queues_.end()) return;
    Queue& q = it->second;
    if (q.waiting.empty()) {
      if (--q.running == 0) queues_.erase(it);
      return;
    }
    next = std::move(q.waiting.front());
    q.waiting.pop_front();
    --waiting_;
  }
  start(connection, std::move(next));
}

}  // namespace fnet::server
