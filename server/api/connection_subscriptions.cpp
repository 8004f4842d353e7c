#include "server/api/connection_subscriptions.hpp"

#include <utility>

#include "server/api/api_params.hpp"

namespace fnet::server {

ConnectionSubscriptions::ConnectionSubscriptions(Registry& registry, std::size_t limit, std::string kind,
                                                 std::function<void(std::uint64_t)> forget)
    : registry_(registry), limit_(limit), kind_(std::move(kind)), forget_(std::move(forget)) {}

void ConnectionSubscriptions::check_room(const rpc::Peer& session) const {
  std::lock_guard lock(mutex_);
  const auto it = sessions_.find(session.id());
  const std::size_t held = it == sessions_.end() ? 0 : it->second.size();
  if (held >= limit_)
    throw rpc::Error(rpc::kTooManySubscriptions,
                     "at most " + std::to_string(limit_) + " " + kind_ + "s per connection");
}

void ConnectionSubscriptions::add(const std::shared_ptr<rpc::Peer>& session, std::uint64_t id) {
  bool first = false;
  {
    std::lock_guard lock(mutex_);
    auto [it, inserted] = sessions_.try_emplace(session->id());
    first = inserted;
    it->second.insert(id);
  }
  session->subscriptions_changed(+1);
  // Outside the lock: on a connection already closed the hook runs at once.
  if (first) session->on_close([self = shared_from_this(), sid = session->id()] { self->release(sid); });
}

void ConnectionSubscriptions::remove(rpc::Peer& session, std::uint64_t id) {
  bool found = false;
  {
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(session.id());
    found = it != sessions_.end() && it->second.erase(id) > 0;
  }
  if (!found)
    invalid("subscription", "parameter 'subscription': no " + kind_ + " " + std::to_string(id) + " on this connection");
  session.subscriptions_changed(-1);
  end(id);
}

void ConnectionSubscriptions::drop(rpc::Peer& session, std::uint64_t id) {
  bool found = false;
  {
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(session.id());
    found = it != sessions_.end() && it->second.erase(id) > 0;
  }
  if (found) session.subscriptions_changed(-1);
  end(id);
}

void ConnectionSubscriptions::end(std::uint64_t id) {
  if (forget_) forget_(id);
  registry_.unsubscribe(id);
}

void ConnectionSubscriptions::release(std::uint64_t session_id) {
  std::set<std::uint64_t> ids;
  {
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(session_id);
    if (it == sessions_.end()) return;
    ids = std::move(it->second);
    sessions_.erase(it);
  }
  for (const std::uint64_t id : ids) end(id);
}

}  // namespace fnet::server
