// A run's store as the registry uses it: written and read under a lock of its own, never under
// the lock every run shares. The registry queues what it settles (under its lock: a copy of a
// pointer, nothing more), in settlement order; a thread that queued writes the queue out after
// releasing the registry's lock, and a read first writes out what is queued, so it sees every
// frame committed before it was asked for. What is written is handed back in order
// (take_written): only then does the registry count a frame as committed.
//
// The file is opened (created, or continued: StoreWriter) at the first write and closed when the
// registry says the run is finished or idle (close); a closed store is reopened for the next
// write, and read read-only meanwhile. A failed open or write is the store's fault: the record
// stays at the head of the queue, nothing queued is dropped, the file is closed, and the queue
// is written out again only by retry(), which reopens the file (continuing what it holds: a
// record the failed attempt did commit is not written twice). The fault lasts until a retry
// writes the head of the queue.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/analysis/analyzed_frame.hpp"
#include "common/run/run_frame.hpp"
#include "common/store/analysis_store.hpp"
#include "server/registry/store_check.hpp"

namespace fnet::server {

class RunStore {
 public:
  using Record = std::variant<RunInfo, std::shared_ptr<const AnalyzedFrame>, RejectedFrame>;

  // A file already at `path` when the store is first opened is continued only once `checker`
  // (if any) passes it: it was not written by this process.
  RunStore(std::filesystem::path path, std::string run_id, std::shared_ptr<StoreChecker> checker = nullptr);
  const std::string& run_id() const { return run_id_; }

  // Thread-safe and cheap (never waits for a write in progress); `at` is when it happened.
  void queue(const RunInfo& info, StoreTime at = store_time_now());
  void queue(std::shared_ptr<const AnalyzedFrame> frame, StoreTime at = store_time_now());
  void queue(const RejectedFrame& rejected, StoreTime at = store_time_now());

  // Writes what is queued, in order, unless the store is at fault; returns when every write
  // queued before the call is done (by this thread or another) or the store is at fault.
  void write_queued();
  // After a fault: reopens the file and writes what is queued. Returns whether the fault is over.
  bool retry();
  // The records written since the last call, in queue order. Call under one lock for every
  // caller, so that what one takes is handled before what the next takes.
  std::vector<Record> take_written();

  // Closes the file when nothing is queued and the store is not at fault; returns whether it is
  // closed. Sealed: never opened for writing again (the server is stopping).
  bool close(bool seal = false);

  // The force network of committed frame `index` (queued frames first written out); nullopt for
  // a frame committed without one. Throws std::runtime_error naming the cause: the store's
  // fault, or the frame not in it.
  std::optional<Frame> network(std::uint32_t index);
  // The diagrams of committed frame `index`, read as network() reads it; throws as it does.
  FrameDiagramSet diagrams(std::uint32_t index);

  // Why the store does not take writes; empty while it does.
  std::string fault() const;
  bool open() const;

 private:
  struct Queued {
    Record record;
    StoreTime at;
  };
  void push(Record record, StoreTime at);
  // With io_mutex_ held: writes the queue out unless at fault (or `retrying`).
  void write_queued_locked(bool retrying);
  // Reads with `read` from the open file, or else from the closed one (read-only), queued frames
  // first written out; a failure names the store's fault, if any.
  template <class Read>
  auto read_locked(Read&& read);
  // With io_mutex_ held: whether the open file already holds the record (after a reopen).
  bool holds_locked(const Record& record) const;

  const std::filesystem::path path_;
  const std::string run_id_;
  const std::shared_ptr<StoreChecker> checker_;

  mutable std::mutex queue_mutex_;  // guards queue_, written_, fault_, open_
  std::deque<Queued> queue_;        // the head is written first; popped once written
  std::vector<Record> written_;
  std::string fault_;
  bool open_ = false;

  std::mutex io_mutex_;  // one thread at a time opens, writes, closes or reads the file
  std::unique_ptr<StoreWriter> writer_;
  bool written_here_ = false;  // the file is this process's own: opened by a StoreWriter here
  bool sealed_ = false;
};

}  // namespace fnet::server
