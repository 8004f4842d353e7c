#include "server/registry/fair_scheduler.hpp"

#include <algorithm>
#include <exception>
#include <iostream>
#include <tuple>

#include <boost/asio/post.hpp>

namespace fnet::server {

std::string run_queue(const std::string& run_id) { return "run " + run_id; }

FairScheduler::FairScheduler(boost::asio::thread_pool& pool, std::size_t threads)
    : pool_(pool), threads_(std::max<std::size_t>(threads, 1)) {}

FairScheduler::~FairScheduler() { wait_idle(); }

void FairScheduler::wait_idle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return workers_ == 0; });
}

void FairScheduler::post(const std::string& queue, Job job) {
  {
    std::lock_guard lock(mutex_);
    queues_[queue].jobs.push_back(std::move(job));
    if (workers_ == threads_) return;  // a running worker takes it when it is its turn
    ++workers_;
  }
  boost::asio::post(pool_, [this] { work(); });
}

std::map<std::string, FairScheduler::Queue>::iterator FairScheduler::next_locked() {
  auto best = queues_.end();
  for (auto it = queues_.begin(); it != queues_.end(); ++it) {
    if (it->second.jobs.empty()) continue;
    if (best == queues_.end() ||
        std::tie(it->second.running, it->second.last_start) < std::tie(best->second.running, best->second.last_start))
      best = it;
  }
  return best;
}

void FairScheduler::work() {
  std::unique_lock lock(mutex_);
  while (true) {
    const auto it = next_locked();
    if (it == queues_.end()) break;
    const std::string name = it->first;
    Queue& q = it->second;
    Job job = std::move(q.jobs.front());
    q.jobs.pop_front();
    ++q.running;
    q.last_start = ++starts_;
    lock.unlock();
    try {
      job();
    } catch (const std::exception& e) {
      std::cerr << "fnet-server: a job of " << name << " failed: " << e.what() << "\n";
    } catch (...) {
      std::cerr << "fnet-server: a job of " << name << " failed\n";
    }
    job = nullptr;  // what it holds is released off the lock
    lock.lock();
    // The queue may have been served by other workers meanwhile, but it cannot have been erased:
    // this job was running.
    const auto done = queues_.find(name);
    --done->second.running;
    if (done->second.running == 0 && done->second.jobs.empty()) queues_.erase(done);
  }
  if (--workers_ == 0) idle_.notify_all();
}

std::map<std::string, std::size_t> FairScheduler::waiting() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::size_t> out;
  for (const auto& [name, q] : queues_)
    if (!q.jobs.empty()) out[name] = q.jobs.size();
  return out;
}

}  // namespace fnet::server
