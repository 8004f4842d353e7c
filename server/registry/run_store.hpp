// A run's store as the registry uses it: written and read under a lock of its own, never under
// the lock every run shares. The registry queues what it settles (under its lock: a copy of a
// pointer, nothing more), in settlement order; a thread that queued writes the queue out after
// releasing the registry's lock, and a read first writes out what is queued, so it sees every
// frame committed before it was asked for.
//
// The file is opened (created, or continued: StoreWriter) at the first write. A failure to open
// or to write stops the writes: the store stays as it was up to the failure, the analysis goes on
// in memory, and problem() says why.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>

#include "common/analysis/analyzed_frame.hpp"
#include "common/run/run_frame.hpp"
#include "common/store/analysis_store.hpp"

namespace fnet::server {

class RunStore {
 public:
  RunStore(std::filesystem::path path, std::string run_id);

  // Thread-safe and cheap (never waits for a write in progress); `at` is when it happened.
  void queue(const RunInfo& info, StoreTime at = store_time_now());
  void queue(std::shared_ptr<const AnalyzedFrame> frame, StoreTime at = store_time_now());
  void queue(const RejectedFrame& rejected, StoreTime at = store_time_now());

  // Writes what is queued, in order; returns when every write queued before the call is done
  // (by this thread or another).
  void write_queued();

  // The force network of committed frame `index` (queued frames first written out); nullopt for
  // a frame committed without one. Throws std::runtime_error naming the cause: the store's
  // problem, or the frame not in it.
  std::optional<Frame> network(std::uint32_t index);

  // Why the store stopped taking writes; empty while it works.
  std::string problem() const;

 private:
  using Record = std::variant<RunInfo, std::shared_ptr<const AnalyzedFrame>, RejectedFrame>;
  struct Queued {
    Record record;
    StoreTime at;
  };
  void push(Record record, StoreTime at);
  // With io_mutex_ held.
  void write_queued_locked();
  void fail_locked(const std::string& what);

  const std::filesystem::path path_;
  const std::string run_id_;

  mutable std::mutex queue_mutex_;  // guards queue_ and problem_
  std::deque<Queued> queue_;
  std::string problem_;

  std::mutex io_mutex_;  // one thread at a time opens, writes or reads the file
  std::unique_ptr<StoreWriter> writer_;
  bool failed_ = false;
};

}  // namespace fnet::server
