// The registry subscriptions each connection holds, of one kind (series or ensemble): the limit
// per connection, unsubscribe's check that an id is this connection's own, and their release when
// the connection closes. The ids are the registry's, shared by every kind, so each kind keeps its
// own sets: series.unsubscribe cannot end an ensemble subscription.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "server/registry/run_registry.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::server {

class ConnectionSubscriptions : public std::enable_shared_from_this<ConnectionSubscriptions> {
 public:
  // `kind` names these subscriptions in errors ("subscription", "ensemble subscription").
  // `forget` is called with each id ended here (by unsubscribe or by the connection closing)
  // before it is unsubscribed from the registry, so that its owner drops what it keeps for it.
  // The close hooks hold this object (make it with std::make_shared), so a connection still
  // releases its subscriptions when it outlives the methods that made them.
  ConnectionSubscriptions(Registry& registry, std::size_t limit, std::string kind,
                          std::function<void(std::uint64_t)> forget = {});

  // Error -32003 when the connection already holds `limit` of this kind.
  void check_room(const rpc::Peer& session) const;
  // Records `id` as the connection's; the first one hooks the release of them all on close. The
  // connection is told how many it holds (a connection that holds one is not idle).
  void add(const std::shared_ptr<rpc::Peer>& session, std::uint64_t id);
  // Ends the connection's subscription `id`; error -32602 on 'subscription' when it holds none such.
  void remove(rpc::Peer& session, std::uint64_t id);
  // Ends `id` without the check: a subscription that failed after it was added.
  void drop(rpc::Peer& session, std::uint64_t id);

 private:
  void end(std::uint64_t id);
  void release(std::uint64_t session_id);

  Registry& registry_;
  const std::size_t limit_;
  const std::string kind_;
  const std::function<void(std::uint64_t)> forget_;
  mutable std::mutex mutex_;
  std::map<std::uint64_t, std::set<std::uint64_t>> sessions_;  // connection -> its subscriptions
};

}  // namespace fnet::server
