// Every run the server knows: frames flow in from the ingest thread and each run's RunPipeline
// decides their order and acceptance (duplicates dropped, out-of-order frames waiting for their
// predecessors, a frame missing for longer than the gap timeout skipped, distances to the
// previous accepted frame). The registry adds the concurrency, running the pipelines' jobs on a
// bounded thread pool under one lock, and the publication: what a pipeline settles is written in
// index order to the run's store, and committed — counted, served, sent to the subscribers — once
// the store holds it. The lock guards memory only: the stores are written and read under locks of
// their own (run_store.hpp) and the subscribers are served from their outboxes (subscriber.hpp),
// both after it is released. A restart reloads every store.
//
// In memory a committed frame is its row: header, predecessor, distances and the counts of its
// networks, not its diagrams' points nor its network. Those are read back from the run's store
// when asked for, through one cache every run shares (frame_cache.hpp), bounded in bytes
// (RegistryLimits::cache_bytes), which also keeps each frame's diagrams as it is committed. What
// waits for its store is held whole until written (RunStore), and each run's pipeline holds the
// diagrams of its last accepted frame, the next distances' predecessor.
//
// A store that cannot be written is the run's fault (RunSummary::store_fault): what waits for it
// stays queued, counted among the frames in flight (so the ingest's bound on them bounds its
// memory too), and tend_stores() retries it. tend_stores() also closes the stores of finished
// runs (every planned frame settled) and of idle ones.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/asio/thread_pool.hpp>

#include "common/analysis/run_pipeline.hpp"
#include "common/run/run_frame.hpp"
#include "common/run/run_status.hpp"
#include "common/store/analysis_store.hpp"
#include "server/registry/fair_scheduler.hpp"
#include "server/registry/frame_cache.hpp"
#include "server/registry/run_store.hpp"
#include "server/registry/store_check.hpp"
#include "server/registry/subscriber.hpp"

namespace fnet::server {

using Clock = PipelineClock;

struct RunSummary {
  std::string run_id;
  bool has_info = false;
  RunInfo info;
  // frames and rejected: those the store holds; unstored: settled, waiting for the store.
  std::size_t frames = 0, rejected = 0, pending = 0, duplicates = 0, skipped = 0, unstored = 0;
  std::string store_fault;  // why the run's store takes no writes; empty while it does
  std::optional<std::uint32_t> first_frame, last_frame;
  double last_rho = 0, last_z = 0;
  int dimension = 2;            // the last committed frame's
  std::optional<double> rho_j;  // where Z first reached 3 among the analyzed frames, interpolated
  // Seconds since the Unix epoch of the last frame received or announcement, kept in the store
  // so that it survives a restart; none for a run known only from a store without times.
  std::optional<StoreTime> last_activity;
  double seconds_since_last_frame = 0;  // since last_activity, or since the server learned of the run
};

// Why a frame's force network cannot be had: names the run, the frame and the cause.
class NetworkUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Why a committed frame's diagrams cannot be read back from its run's store: names the run, the
// frame and the cause.
class DiagramsUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Counters {
  std::size_t received = 0, analyzed = 0, rejected = 0, duplicates = 0, late = 0, skipped = 0, malformed = 0;
};

struct RegistryLimits {
  std::chrono::milliseconds gap_timeout{30000};  // a missing frame is skipped after this
  std::size_t reasons_kept = 100;                // most recent rejection reasons reported by status
  std::chrono::milliseconds store_retry{2000};   // a store at fault is retried this often
  std::chrono::milliseconds store_idle{600000};  // a store written to no more for this long is closed
  std::size_t max_contacts_per_grain = 24;       // FrameRules; 0: no bound
  // How the stores this registry did not write are checked before they are read (store_check.hpp);
  // none: read unchecked.
  std::optional<StoreCheckOptions> store_check;
  std::size_t cache_bytes = 64u << 20;  // the bound of the frames read back from the stores (FrameCache)
};

class Registry {
 public:
  // The analysis jobs of each run go to `scheduler` in the run's own queue (run_queue).
  Registry(std::filesystem::path data_dir, FairScheduler& scheduler, RegistryLimits limits = {});
  // With a scheduler of its own over `pool`, taking as many threads at once as the machine has.
  Registry(std::filesystem::path data_dir, boost::asio::thread_pool& pool, RegistryLimits limits = {});
  // Waits until what was committed is written to the stores and delivered. The pool's jobs must
  // have ended (the server joins the pool first).
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // Reads every store in the data directory, each checked first (RegistryLimits::store_check);
  // returns messages about stores that could not be read.
  std::vector<std::string> load();

  // Reads the stores placed in the data directory since (RUN.h5 of a run the server does not know,
  // e.g. written by fnet-analyze store, which must have finished): the runs adopted, and messages
  // about stores that could not be read.
  struct Adopted {
    std::vector<std::string> runs;
    std::vector<std::string> problems;
  };
  Adopted adopt_new_stores();
  // The stores of the data directory the last load or rescan refused (a corrupt file, a file
  // that is not a regular one, a run id that is not a file name): each names its file and why.
  std::vector<std::string> refused_stores() const;

  void on_info(const RunInfo& info);
  // Called with each new announcement of a run, once it is recorded, off the registry's lock: from
  // then on the run belongs to its ensemble, with the frames it had committed before. One listener
  // (the ensemble subscriptions, which must then recompute even when the run commits nothing more).
  void on_announcement(std::function<void(const RunInfo&)> listener);
  void on_frame(RunFrame frame);
  // A frame refused before it was read whole (too large): rejected in its run, in its place.
  void on_refused(const FrameHeader& header, const std::string& reason);
  void on_malformed(const std::string& reason);
  // Skips frames missing for longer than the gap timeout; call periodically.
  void check_gaps();

  // Frames received and not yet committed, over all runs (in analysis, or waiting for their
  // store), and the bytes they hold (frame_bytes): the ingest's back-pressure measures.
  std::size_t in_flight() const;
  std::size_t in_flight_bytes() const;

  // Call periodically (from one thread): retries the stores at fault whose turn has come, closes
  // the stores of finished and idle runs, and returns the status of each run contacted since the
  // server started whose status changed since the last call (RunStatus::server left empty).
  std::vector<RunStatus> tend_stores();
  // At a stop: writes out what is queued for the stores (what the analysis committed) and closes
  // them for good; what is settled later is not written (it is received again after a restart).
  void seal_stores();
  std::size_t stores_open() const;

  std::vector<RunSummary> runs() const;
  std::optional<RunSummary> run(const std::string& run_id) const;
  bool has_run(const std::string& run_id) const;
  std::vector<RejectedFrame> rejected(const std::string& run_id) const;
  // The rows of a run's committed frames in index order: without their diagrams' points (frame()
  // has them).
  std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> frames(const std::string& run_id) const;
  // The row of a committed frame; null when the run has no such frame.
  std::shared_ptr<const AnalyzedFrame> row(const std::string& run_id, std::uint32_t index) const;
  // A committed frame with its diagrams, from the cache or else read back from the run's store
  // (off the registry's lock); null when the run has no such frame. Throws DiagramsUnavailable.
  std::shared_ptr<const AnalyzedFrame> frame(const std::string& run_id, std::uint32_t index) const;
  std::string newest_run() const;
  // The force network of a committed frame, read back from the run's store: the committed frames
  // in memory hold their diagrams only. Throws NetworkUnavailable.
  Frame network(const std::string& run_id, std::uint32_t index) const;
  FrameCacheStats cache_stats() const { return cache_.stats(); }

  // A run and the rows of its committed frames in index order.
  struct MemberRun {
    std::string run_id;
    std::vector<std::shared_ptr<const AnalyzedFrame>> frames;
  };
  // The runs announced as members of `ensemble`, in name order, taken under one lock so that the
  // members are seen at one instant. Empty when no run names it.
  std::vector<MemberRun> ensemble_members(const std::string& ensemble) const;

  // Registers a subscriber (subscriber.hpp). It receives the committed points of `run_id` (of
  // every run when empty) with frame index > since, then every point committed after, once each
  // and in frame order per run, as fast as the subscriber has room for them.
  std::uint64_t subscribe(const std::string& run_id, std::optional<std::uint32_t> since,
                          std::shared_ptr<Subscriber> subscriber);
  void unsubscribe(std::uint64_t id);
  std::size_t subscriptions() const;

  Counters counters() const;
  std::deque<std::string> recent_rejections() const;
  double frames_per_second() const;  // commits over the last 10 s
  double oldest_pending_seconds() const;

 private:
  struct Run {
    std::string run_id;
    bool has_info = false;
    RunInfo info;
    RunPipeline pipeline;                                                     // the order and acceptance of its frames
    std::map<std::uint32_t, std::shared_ptr<const AnalyzedFrame>> committed;  // rows
    std::vector<RejectedFrame> rejected;
    std::optional<StoreTime> last_activity;
    StoreTime known_since = store_time_now();
    std::shared_ptr<RunStore> store;   // never null
    std::size_t unstored = 0;          // records queued for the store and not yet committed
    std::uint32_t stored_through = 0;  // every frame below it is settled in the store
    Clock::time_point last_write = Clock::now(), next_retry = Clock::now();
    bool contacted = false;  // a frame or announcement came since the server started
    std::optional<RunStatus> status_sent;
  };
  // A subscription's place in the runs it follows. Its points are read from the committed frames
  // when they are delivered, a page at a time, never copied ahead: a subscription holds no backlog,
  // whatever the length of the runs or the pace of its subscriber.
  struct Outbox {
    std::uint64_t id = 0;
    std::string run_id;  // empty: every run
    std::shared_ptr<Subscriber> subscriber;
    bool marked = false;  // in ready_; under the registry's lock
    std::mutex mutex;     // guards what follows; taken after the registry's lock, never before it
    std::map<std::string, std::uint32_t, std::less<>> delivered;  // per run: the last frame delivered
    bool delivering = false, again = false, ended = false;
  };

  Run& run_locked(const std::string& run_id);
  // Marks an outbox for delivery once the lock is released.
  void mark_locked(const std::shared_ptr<Outbox>& outbox);
  // The next points of a subscription, at most `limit`, in frame order per run.
  std::vector<SeriesPoint> page(Outbox& outbox, std::size_t limit) const;
  // The registry's part of a frame's arrival (on_frame, on_refused): the counters, the run id's
  // check, the run's activity, then the admission `admit` makes and the jobs it allows.
  template <class Admit>
  void arrive_locked(const FrameHeader& header, const std::string& label, Admit&& admit);
  // Runs `f` under the lock; then, off the lock, writes out the stores it queued writes to and
  // delivers the points it queued (a subscriber sees a point once its frame is in the store).
  template <class F>
  auto locked_then_deliver(F&& f);
  void deliver(const std::shared_ptr<Outbox>& outbox);
  // Runs jobs on the pool; each hands its outcome back to the run's pipeline under the lock.
  void post_locked(const Run& run, DiagramJob job);
  void post_locked(const Run& run, std::vector<DistanceJob> jobs);
  // Publishes what the run's pipeline settled: the store, the subscribers, the counters.
  void publish_locked(Run& run);
  void commit_locked(Run& run, std::shared_ptr<const AnalyzedFrame> frame);
  void reject_locked(Run& run, const RejectedFrame& rejected);
  // What the stores wrote: frames committed, rejections recorded, in the order written.
  void adopt_written_locked(const std::vector<std::shared_ptr<RunStore>>& stores);
  // Writes `stores` out off the lock, commits what they wrote and delivers what that queued.
  void write_then_deliver(const std::vector<std::shared_ptr<RunStore>>& stores,
                          std::vector<std::shared_ptr<Outbox>> ready);
  RunStatus status_locked(const Run& run) const;
  // Queues a write to the run's store, written out when the lock is released.
  template <class Record>
  void store_locked(Run& run, Record&& record);
  void note_rejection_locked(std::string reason);
  RunSummary summary_locked(const std::string& id, const Run& run) const;

  const std::filesystem::path data_dir_;
  std::unique_ptr<FairScheduler> own_scheduler_;  // with the pool constructor only
  FairScheduler& scheduler_;
  const RegistryLimits limits_;
  const std::shared_ptr<StoreChecker> checker_;  // null: stores read unchecked
  mutable FrameCache cache_;
  // load() and adopt_new_stores(): with only_new, skips the stores of known runs and lists the
  // runs it adopts there. Reads the files off the lock.
  std::vector<std::string> load_stores(std::vector<std::string>* only_new);
  std::function<void(const RunInfo&)> announcement_listener_;
  mutable std::mutex mutex_;
  std::map<std::string, Run> runs_;
  std::map<std::uint64_t, std::shared_ptr<Outbox>> subscriptions_;
  std::vector<std::shared_ptr<Outbox>> ready_;           // outboxes with points committed since the last delivery
  std::vector<std::shared_ptr<RunStore>> stores_ready_;  // stores with writes queued since then
  std::size_t flushing_ = 0;  // threads writing out stores and delivering points after the lock
  std::condition_variable flushed_;
  std::uint64_t next_subscription_ = 1;
  Counters counters_;
  std::deque<std::string> recent_rejections_;
  std::vector<std::string> refused_stores_;
  std::deque<Clock::time_point> recent_commits_;
};

}  // namespace fnet::server
