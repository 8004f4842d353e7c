// The analysis pool's jobs, taken from the queues of their owners in turn: each run is a queue,
// and the API's heavy queries one more. A queue's jobs start in the order they were posted; which
// queue goes next is the rule below, not the order of posting, so that one owner with many long
// jobs (a run of heavy frames, a client's batch of distances) cannot make the others wait for all
// of them.
//
// Rule: when a pool thread is free, it takes the next job of the queue that has the fewest jobs
// running, among those with jobs waiting; of those, the one that started a job least recently.
// Hence a queue with jobs waiting and none running is served at the next free thread unless other
// such queues are ahead of it, each for one job: a job waits at most for the jobs running when it
// came (one per thread) and one job of each other queue. Several queues that keep jobs waiting
// share the threads evenly; a queue alone uses every thread.
//
// Jobs run on the pool's threads; at most `threads` at once, never more than the pool has. post()
// may be called from any thread, from a job too. A job that throws is reported on stderr and the
// next one runs. Joining the pool waits for every job posted, those posted by jobs included.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <boost/asio/thread_pool.hpp>

namespace fnet::server {

class FairScheduler {
 public:
  using Job = std::function<void()>;

  // `threads`: how many jobs may run at once, the pool's thread count.
  FairScheduler(boost::asio::thread_pool& pool, std::size_t threads);
  ~FairScheduler();  // wait_idle()
  FairScheduler(const FairScheduler&) = delete;
  FairScheduler& operator=(const FairScheduler&) = delete;

  void post(const std::string& queue, Job job);

  // Blocks until every job posted has run and no pool thread is inside the scheduler any more.
  void wait_idle();

  // Jobs waiting (not running) per queue, for status and tests; queues with none are left out.
  std::map<std::string, std::size_t> waiting() const;

 private:
  struct Queue {
    std::deque<Job> jobs;
    std::size_t running = 0;
    std::uint64_t last_start = 0;  // the start counter when it last started a job; 0: never
  };

  // A pool thread's loop: takes jobs by the rule until none waits.
  void work();
  // The queue whose job starts next, or end() when no job waits. Under mutex_.
  std::map<std::string, Queue>::iterator next_locked();

  boost::asio::thread_pool& pool_;
  const std::size_t threads_;
  mutable std::mutex mutex_;
  std::condition_variable idle_;         // notified when workers_ falls to 0
  std::map<std::string, Queue> queues_;  // a queue with no job waiting or running is erased
  std::size_t workers_ = 0;              // pool threads inside work(), <= threads_
  std::uint64_t starts_ = 0;             // jobs started so far
};

// The queue of a run's analysis jobs, and the API's: distinct for every run id (run ids have no
// spaces).
std::string run_queue(const std::string& run_id);
inline const std::string kApiQueue = "api queries";

}  // namespace fnet::server
