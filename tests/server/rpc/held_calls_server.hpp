// A JSON-RPC server on a real loopback socket whose methods the test controls: "echo" ends at
// once with its params; "big" ends at once with a string of params.n bytes; "hold" ends at once
// and marks its connection as holding a subscription; "fail" throws; "slow" ends when the test
// releases it, from another thread; "late_error" ends later with an rpc::Error. Every call that
// reaches the handler is counted.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without it
#include <vector>

#include <boost/asio.hpp>

#include "server/rpc/rpc_server.hpp"

namespace fnet::rpc {

inline std::string request_line(int id, const std::string& method, const json& params = json::object()) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump();
}

class HeldCallsServer {
 public:
  explicit HeldCallsServer(ServerLimits limits = {}, Access access = {}) {
    server_.emplace(
        io_, "127.0.0.1", 0,
        [this](const std::string& method, const json& params, const std::shared_ptr<Peer>& peer, Completion done) {
          ++calls;
          if (method == "echo") return done(params, nullptr);
          if (method == "big") return done(std::string(params.value("n", std::size_t{0}), 'x'), nullptr);
          if (method == "hold") {
            peer->subscriptions_changed(+1);
            return done(true, nullptr);
          }
          if (method == "fail") throw Error(kInvalidParams, "bad");
          std::lock_guard lock(mutex_);
          held_.push_back({method, params, std::move(done)});
          changed_.notify_all();
        },
        limits, std::move(access));
    thread_ = std::thread([this] { io_.run(); });
  }
  ~HeldCallsServer() {
    release_all();
    server_->stop();
    io_.stop();
    thread_.join();
  }
  unsigned short port() const { return server_->port(); }
  // Waits until `n` slow calls are held.
  bool wait_held(std::size_t n, std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return held_.size() >= n; });
  }
  std::size_t held() {
    std::lock_guard lock(mutex_);
    return held_.size();
  }
  // Ends the oldest held call from a thread of its own, as the analysis pool would.
  void release_one() {
    Held h;
    {
      std::lock_guard lock(mutex_);
      h = std::move(held_.front());
      held_.erase(held_.begin());
    }
    std::thread([h = std::move(h)] {
      if (h.method == "late_error")
        h.done(nullptr, std::make_exception_ptr(Error(kNoNetwork, "later")));
      else
        h.done(json{{"slow", h.params}}, nullptr);
    }).join();
  }
  void release_all() {
    while (held() > 0) release_one();
  }
  std::atomic<int> calls{0};

 private:
  struct Held {
    std::string method;
    json params;
    Completion done;
  };
  boost::asio::io_context io_;
  std::optional<Server> server_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Held> held_;
};

}  // namespace fnet::rpc
