#include "server/registry/run_registry.hpp"

#include <algorithm>
#include <iostream>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>

#include "common/analysis/jamming.hpp"
#include "common/run/run_names.hpp"
#include "server/registry/announcement_check.hpp"

namespace fnet::server {
namespace {

std::shared_ptr<StoreChecker> make_checker(const RegistryLimits& limits) {
  return limits.store_check ? std::make_shared<StoreChecker>(*limits.store_check) : nullptr;
}

// What memory keeps of a committed frame: all but its diagrams' points and its network.
std::shared_ptr<const AnalyzedFrame> committed_row(const AnalyzedFrame& frame) {
  auto row = std::make_shared<AnalyzedFrame>();
  row->header = frame.header;
  row->dimension = frame.dimension;
  row->previous = frame.previous;
  row->distances = frame.distances;
  for (const ForceKind force : {ForceKind::normal, ForceKind::tangential}) {
    const FrameDiagrams& from = frame.diagrams[force];
    FrameDiagrams& to = force == ForceKind::normal ? row->diagrams.normal : row->diagrams.tangential;
    to.vertices = from.vertices, to.edges = from.edges, to.triangles = from.triangles;
  }
  return row;
}

}  // namespace

Registry::Registry(std::filesystem::path data_dir, FairScheduler& scheduler, RegistryLimits limits)
    : data_dir_(std::move(data_dir)),
      scheduler_(scheduler),
      limits_(limits),
      checker_(make_checker(limits)),
      cache_(limits.cache_bytes) {
  std::filesystem::create_directories(data_dir_);
}

Registry::Registry(std::filesystem::path data_dir, boost::asio::thread_pool& pool, RegistryLimits limits)
    : data_dir_(std::move(data_dir)),
      own_scheduler_(std::make_unique<FairScheduler>(pool, std::max(1u, std::thread::hardware_concurrency()))),
      scheduler_(*own_scheduler_),
      limits_(limits),
      checker_(make_checker(limits)),
      cache_(limits.cache_bytes) {
  std::filesystem::create_directories(data_dir_);
}

Registry::~Registry() {
  if (own_scheduler_) own_scheduler_->wait_idle();  // its jobs use this registry
  std::unique_lock lock(mutex_);
  flushed_.wait(lock, [this] { return flushing_ == 0; });
}

template <class F>
auto Registry::locked_then_deliver(F&& f) {
  std::vector<std::shared_ptr<Outbox>> ready;
  std::vector<std::shared_ptr<RunStore>> stores;
  const auto take = [&] {
    ready.swap(ready_);
    for (const auto& outbox : ready) outbox->marked = false;
    stores.swap(stores_ready_);
    if (!ready.empty() || !stores.empty()) ++flushing_;
  };
  const auto flush = [&] {
    if (ready.empty() && stores.empty()) return;
    write_then_deliver(stores, std::move(ready));
    std::lock_guard lock(mutex_);
    if (--flushing_ == 0) flushed_.notify_all();
  };
  if constexpr (std::is_void_v<decltype(f())>) {
    {
      std::lock_guard lock(mutex_);
      f();
      take();
    }
    flush();
  } else {
    auto result = [&] {
      std::lock_guard lock(mutex_);
      auto r = f();
      take();
      return r;
    }();
    flush();
    return result;
  }
}

void Registry::write_then_deliver(const std::vector<std::shared_ptr<RunStore>>& stores,
                                  std::vector<std::shared_ptr<Outbox>> ready) {
  for (const auto& store : stores) store->write_queued();
  if (!stores.empty()) {
    std::lock_guard lock(mutex_);
    adopt_written_locked(stores);
    for (const auto& outbox : ready_) outbox->marked = false;
    ready.insert(ready.end(), ready_.begin(), ready_.end());
    ready_.clear();
  }
  for (const auto& outbox : ready) deliver(outbox);
}

template <class Record>
void Registry::store_locked(Run& run, Record&& record) {
  run.store->queue(std::forward<Record>(record));
  ++run.unstored;
  run.last_write = Clock::now();
  if (std::find(stores_ready_.begin(), stores_ready_.end(), run.store) == stores_ready_.end())
    stores_ready_.push_back(run.store);
}

// Under the lock, so that the records one thread takes are committed before those the next takes.
void Registry::adopt_written_locked(const std::vector<std::shared_ptr<RunStore>>& stores) {
  for (const auto& store : stores) {
    const auto it = runs_.find(store->run_id());
    if (it == runs_.end()) continue;
    Run& run = it->second;
    for (RunStore::Record& record : store->take_written()) {
      --run.unstored;
      if (auto* frame = std::get_if<std::shared_ptr<const AnalyzedFrame>>(&record)) {
        run.stored_through = std::max(run.stored_through, (*frame)->header.index + 1);
        commit_locked(run, std::move(*frame));
      } else if (const auto* rejected = std::get_if<RejectedFrame>(&record)) {
        run.stored_through = std::max(run.stored_through, rejected->index + 1);
        run.rejected.push_back(*rejected);
      }
    }
  }
}

void Registry::mark_locked(const std::shared_ptr<Outbox>& outbox) {
  if (std::exchange(outbox->marked, true)) return;
  ready_.push_back(outbox);
}

std::vector<SeriesPoint> Registry::page(Outbox& o, std::size_t limit) const {
  std::vector<SeriesPoint> out;
  std::lock_guard lock(mutex_);
  std::lock_guard outbox_lock(o.mutex);
  const auto follow = [&](const std::string& rid, const Run& run) {
    const auto cursor = o.delivered.find(rid);
    for (auto it = cursor != o.delivered.end() ? run.committed.upper_bound(cursor->second) : run.committed.begin();
         it != run.committed.end() && out.size() < limit; ++it)
      out.push_back({rid, it->second->header, it->second->previous, it->second->distances, run.info.ensemble});
  };
  if (!o.run_id.empty()) {
    if (const auto it = runs_.find(o.run_id); it != runs_.end()) follow(it->first, it->second);
    return out;
  }
  for (auto it = runs_.begin(); it != runs_.end() && out.size() < limit; ++it) follow(it->first, it->second);
  return out;
}

// One thread at a time delivers an outbox, a page read at a time, while its subscriber has room. A call
// meanwhile (a commit, or the subscriber's resume) sets `again`, so the loop reads once more before
// it lets go: nothing committed is left undelivered.
void Registry::deliver(const std::shared_ptr<Outbox>& outbox) {
  constexpr std::size_t kPage = 64;
  Outbox& o = *outbox;
  {
    std::lock_guard lock(o.mutex);
    if (o.ended) return;
    if (o.delivering) {
      o.again = true;
      return;
    }
    o.delivering = true;
  }
  const auto resume = [this, weak = std::weak_ptr<Outbox>(outbox)] {
    if (const auto again = weak.lock()) deliver(again);
  };
  const auto ended = [&o] {
    std::lock_guard lock(o.mutex);
    return o.ended;
  };
  bool gone = false;
  while (true) {
    {
      std::lock_guard lock(o.mutex);
      o.again = false;
    }
    // The subscriber is asked for room before each point: a page may be more than it has.
    bool full = false;
    while (!gone && !full && !ended() && o.subscriber->ready(resume)) {
      const std::vector<SeriesPoint> points = page(o, kPage);
      if (points.empty()) break;
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (k > 0 && !o.subscriber->ready(resume)) {
          full = true;
          break;
        }
        if (!o.subscriber->deliver(o.id, points[k])) {
          gone = true;
          break;
        }
        std::lock_guard lock(o.mutex);
        if (o.ended) break;
        o.delivered[points[k].run_id] = points[k].header.index;
      }
    }
    std::lock_guard lock(o.mutex);
    if (o.again && !o.ended && !gone) continue;
    o.delivering = false;
    break;
  }
  if (gone) unsubscribe(o.id);
}

std::vector<std::string> Registry::load() { return load_stores(nullptr); }

Registry::Adopted Registry::adopt_new_stores() {
  Adopted out;
  out.problems = load_stores(&out.runs);
  return out;
}

// The files are listed under the lock and read off it; each run read is installed under the lock.
std::vector<std::string> Registry::load_stores(std::vector<std::string>* only_new) {
  std::vector<std::filesystem::path> paths;
  {
    std::lock_guard lock(mutex_);
    for (const auto& entry : std::filesystem::directory_iterator(data_dir_)) {
      if (entry.path().extension() != ".h5") continue;
      // A rescan takes only the stores of runs the server does not know: the others it writes itself.
      if (only_new && runs_.count(entry.path().stem().string())) continue;
      paths.push_back(entry.path());
    }
  }
  std::vector<std::string> problems;
  const std::vector<std::string> refused =
      checker_ ? checker_->refusals(paths) : std::vector<std::string>(paths.size());
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const std::filesystem::path& path = paths[k];
    if (!refused[k].empty()) {
      problems.push_back(refused[k]);
      continue;
    }
    try {
      StoredRun stored = read_store_in_data_dir(path);
      std::lock_guard lock(mutex_);
      if (only_new && runs_.count(stored.info.run_id)) continue;  // it started streaming meanwhile
      Run& run = run_locked(stored.info.run_id);
      run.has_info = stored.has_info;
      run.last_activity = stored.last_activity();
      if (stored.has_info) run.info = stored.info;
      std::vector<std::uint32_t> settled;
      for (const AnalyzedFrame& f : stored.frames) {
        settled.push_back(f.header.index);
        run.committed[f.header.index] = committed_row(f);
      }
      for (const RejectedFrame& r : stored.rejected) settled.push_back(r.index);
      run.rejected = std::move(stored.rejected);
      run.pipeline.resume(settled, stored.frames.empty()
                                       ? nullptr
                                       : std::make_shared<const AnalyzedFrame>(std::move(stored.frames.back())));
      run.pipeline.release_predecessor();  // read back when the run's next frame comes
      if (only_new) only_new->push_back(run.run_id);
    } catch (const std::exception& e) {
      problems.push_back(e.what());
    }
  }
  // Every scan reads each store the server does not serve, so its problems are all the refused ones.
  std::lock_guard lock(mutex_);
  refused_stores_ = problems;
  return problems;
}

std::vector<std::string> Registry::refused_stores() const {
  std::lock_guard lock(mutex_);
  return refused_stores_;
}

Registry::Run& Registry::run_locked(const std::string& run_id) {
  auto [it, created] = runs_.try_emplace(run_id);
  Run& run = it->second;
  if (created) {
    run.run_id = run_id;
    run.info.run_id = run_id;
    run.pipeline = RunPipeline(limits_.gap_timeout, EssentialConvention::floor,
                               FrameRules{.max_contacts_per_grain = limits_.max_contacts_per_grain});
    run.store = std::make_shared<RunStore>(store_path(data_dir_, run_id), run_id, checker_);
  }
  return run;
}

void Registry::note_rejection_locked(std::string reason) {
  // The most recent reasons_kept reasons, whatever their source.
  recent_rejections_.push_back(std::move(reason));
  while (recent_rejections_.size() > limits_.reasons_kept) recent_rejections_.pop_front();
}

void Registry::on_info(const RunInfo& info) {
  const auto listener = locked_then_deliver([&]() -> std::function<void(const RunInfo&)> {
    if (const std::string problem = announcement_problem(info); !problem.empty()) {
      ++counters_.malformed;
      note_rejection_locked("run announcement rejected: " + problem);
      std::cerr << "fnet-server: run announcement rejected: " << problem << "\n";
      return nullptr;
    }
    Run& run = run_locked(info.run_id);
    if (run.has_info && run.info == info) return nullptr;  // repeated announcement (a restarted reader)
    run.has_info = true;
    run.info = info;
    run.contacted = true;
    run.last_activity = store_time_now();
    store_locked(run, info);
    return announcement_listener_;
  });
  if (listener) listener(info);
}

void Registry::on_announcement(std::function<void(const RunInfo&)> listener) {
  std::lock_guard lock(mutex_);
  announcement_listener_ = std::move(listener);
}

void Registry::on_malformed(const std::string& reason) {
  std::lock_guard lock(mutex_);
  ++counters_.malformed;
  note_rejection_locked(reason);
}

template <class Admit>
void Registry::arrive_locked(const FrameHeader& header, const std::string& label, Admit&& admit) {
  ++counters_.received;
  if (const std::string problem = run_id_problem(header.run_id); !problem.empty()) {
    ++counters_.malformed;
    note_rejection_locked(label + ": rejected: " + problem);
    return;
  }
  Run& run = run_locked(header.run_id);
  run.contacted = true;
  run.last_activity = store_time_now();
  RunPipeline::Admission admission = admit(run.pipeline);
  switch (admission.arrival) {
    case RunPipeline::Arrival::duplicate:
      ++counters_.duplicates;
      return;
    case RunPipeline::Arrival::late:
      ++counters_.late;
      break;
    case RunPipeline::Arrival::queued:
      post_locked(run, std::move(*admission.job));
      break;
    case RunPipeline::Arrival::refused:
      post_locked(run, std::move(admission.distance_jobs));
      break;
  }
  publish_locked(run);
}

void Registry::on_frame(RunFrame frame) {
  locked_then_deliver([&] {
    const FrameHeader header = frame.header;
    arrive_locked(header, frame.frame.label,
                  [&](RunPipeline& pipeline) { return pipeline.admit(std::move(frame), Clock::now()); });
  });
}

void Registry::on_refused(const FrameHeader& header, const std::string& reason) {
  locked_then_deliver([&] {
    arrive_locked(header, frame_label(header.run_id, header.index),
                  [&](RunPipeline& pipeline) { return pipeline.refuse(header, reason, Clock::now()); });
  });
}

void Registry::post_locked(const Run& run, DiagramJob job) {
  scheduler_.post(run_queue(run.run_id),
                  [this, id = run.run_id, job = std::move(job), released = run.pipeline.released_predecessor()] {
                    DiagramOutcome outcome = job.run();
                    // A released predecessor is read back (off the lock) before the outcome is handed back.
                    std::shared_ptr<const AnalyzedFrame> predecessor;
                    if (released && outcome.diagrams) try {
                        predecessor = frame(id, *released);
                      } catch (const std::exception& e) {
                        std::cerr << "fnet-server: " << e.what() << "\n";
                      }
                    locked_then_deliver([&] {
                      Run& r = runs_.at(id);
                      r.pipeline.restore_predecessor(std::move(predecessor));
                      post_locked(r, r.pipeline.analyzed(std::move(outcome)));
                      publish_locked(r);
                    });
                  });
}

void Registry::post_locked(const Run& run, std::vector<DistanceJob> jobs) {
  for (DistanceJob& job : jobs)
    scheduler_.post(run_queue(run.run_id), [this, id = run.run_id, job = std::move(job)] {
      const DistanceOutcome outcome = job.run();
      locked_then_deliver([&] {
        Run& r = runs_.at(id);
        r.pipeline.measured(outcome);
        publish_locked(r);
      });
    });
}

void Registry::publish_locked(Run& run) {
  for (Settlement& s : run.pipeline.take_settled()) {
    if (auto* accepted = std::get_if<std::shared_ptr<const AnalyzedFrame>>(&s)) {
      store_locked(run, std::move(*accepted));
    } else if (const auto* rejected = std::get_if<RejectedFrame>(&s)) {
      reject_locked(run, *rejected);
    } else if (const auto* skipped = std::get_if<SkippedFrames>(&s)) {
      counters_.skipped += skipped->last - skipped->first + 1;
      note_rejection_locked("run " + run.run_id + ": frames " + std::to_string(skipped->first) + ".." +
                            std::to_string(skipped->last) + " never arrived; skipped after the gap timeout");
    }
  }
  const auto horizon = Clock::now() - std::chrono::seconds(10);
  while (!recent_commits_.empty() && recent_commits_.front() < horizon) recent_commits_.pop_front();
}

// The store and the subscribers see index order, the pipeline's: a frame settled is written to
// the store, and committed once written.
void Registry::commit_locked(Run& run, std::shared_ptr<const AnalyzedFrame> frame) {
  if (frame->network) {  // the store keeps the network
    auto kept = std::make_shared<AnalyzedFrame>(*frame);
    kept->network.reset();
    frame = std::move(kept);
  }
  ++counters_.analyzed;
  recent_commits_.push_back(Clock::now());
  const std::uint32_t index = frame->header.index;
  run.committed[index] = committed_row(*frame);
  cache_.keep(run.run_id, index, std::move(frame));
  for (const auto& [id, outbox] : subscriptions_)
    if (outbox->run_id.empty() || outbox->run_id == run.run_id) mark_locked(outbox);
}

void Registry::reject_locked(Run& run, const RejectedFrame& rejected) {
  ++counters_.rejected;
  note_rejection_locked(rejected.reason);
  std::cerr << "fnet-server: rejected " << rejected.reason << "\n";
  store_locked(run, rejected);
}

void Registry::check_gaps() {
  locked_then_deliver([&] {
    const auto now = Clock::now();
    for (auto& [id, run] : runs_) {
      post_locked(run, run.pipeline.skip_gaps(now));
      publish_locked(run);
    }
  });
}

std::size_t Registry::in_flight() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, run] : runs_) n += run.pipeline.pending() + run.unstored;
  return n;
}

RunStatus Registry::status_locked(const Run& run) const {
  RunStatus s;
  s.run_id = run.run_id;
  // With nothing in analysis or waiting for the store, every frame below the pipeline's frontier
  // is in the store or was skipped; otherwise only those up to the last record written are known
  // to be (the frontier passes a frame once its diagrams are done, before its distances).
  s.settled_through = run.unstored == 0 && run.pipeline.pending() == 0 ? run.pipeline.frontier() : run.stored_through;
  s.stored = static_cast<std::uint32_t>(run.committed.size());
  s.store_fault = run.store->fault();
  return s;
}

std::vector<RunStatus> Registry::tend_stores() {
  std::vector<std::shared_ptr<RunStore>> retry, close;
  {
    std::lock_guard lock(mutex_);
    const auto now = Clock::now();
    for (auto& [id, run] : runs_) {
      if (!run.store->fault().empty()) {
        if (now >= run.next_retry) {
          run.next_retry = now + limits_.store_retry;
          retry.push_back(run.store);
        }
        continue;
      }
      const bool finished = run.has_info && run.info.frames > 0 && run.pipeline.frontier() >= run.info.frames;
      if (run.unstored == 0 && run.pipeline.pending() == 0 &&
          (finished || now - run.last_write >= limits_.store_idle)) {
        run.pipeline.release_predecessor();  // a run no longer live keeps no diagrams
        if (run.store->open()) close.push_back(run.store);
      }
    }
  }
  for (const auto& store : retry) store->retry();
  for (const auto& store : close) store->close();  // declines if a write came meanwhile
  {
    std::lock_guard lock(mutex_);
    ++flushing_;
  }
  write_then_deliver(retry, {});
  std::vector<RunStatus> changed;
  std::lock_guard lock(mutex_);
  if (--flushing_ == 0) flushed_.notify_all();
  for (auto& [id, run] : runs_) {
    if (!run.contacted) continue;
    RunStatus now = status_locked(run);
    if (run.status_sent == now) continue;
    run.status_sent = now;
    changed.push_back(std::move(now));
  }
  return changed;
}

void Registry::seal_stores() {
  std::vector<std::shared_ptr<RunStore>> stores;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, run] : runs_) stores.push_back(run.store);
  }
  for (const auto& store : stores) {
    store->write_queued();
    store->close(true);
  }
}

std::size_t Registry::stores_open() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, run] : runs_) n += run.store->open();
  return n;
}

std::size_t Registry::in_flight_bytes() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, run] : runs_) n += run.pipeline.pending_bytes();
  return n;
}

RunSummary Registry::summary_locked(const std::string& id, const Run& run) const {
  RunSummary s;
  s.run_id = id;
  s.has_info = run.has_info;
  s.info = run.info;
  s.frames = run.committed.size();
  s.rejected = run.rejected.size();
  s.pending = run.pipeline.pending();
  s.duplicates = run.pipeline.counts().duplicates;
  s.skipped = run.pipeline.counts().skipped;
  s.unstored = run.unstored;
  s.store_fault = run.store->fault();
  if (!run.committed.empty()) {
    s.first_frame = run.committed.begin()->first;
    s.last_frame = run.committed.rbegin()->first;
    s.last_rho = run.committed.rbegin()->second->header.rho;
    s.last_z = run.committed.rbegin()->second->header.z;
    s.dimension = run.committed.rbegin()->second->dimension;
    std::vector<double> rho, z;
    rho.reserve(run.committed.size());
    z.reserve(run.committed.size());
    for (const auto& [index, frame] : run.committed) {
      rho.push_back(frame->header.rho);
      z.push_back(frame->header.z);
    }
    s.rho_j = jamming_density(rho, z);
  }
  s.last_activity = run.last_activity;
  s.seconds_since_last_frame = store_time_now() - run.last_activity.value_or(run.known_since);
  return s;
}

std::vector<RunSummary> Registry::runs() const {
  std::vector<RunSummary> out;
  std::lock_guard lock(mutex_);
  for (const auto& [id, run] : runs_) out.push_back(summary_locked(id, run));
  return out;
}

std::optional<RunSummary> Registry::run(const std::string& run_id) const {
  std::lock_guard lock(mutex_);
  const auto it = runs_.find(run_id);
  if (it == runs_.end()) return std::nullopt;
  return summary_locked(it->first, it->second);
}

bool Registry::has_run(const std::string& run_id) const {
  std::lock_guard lock(mutex_);
  return runs_.count(run_id) != 0;
}

std::vector<RejectedFrame> Registry::rejected(const std::string& run_id) const {
  std::lock_guard lock(mutex_);
  const auto it = runs_.find(run_id);
  return it == runs_.end() ? std::vector<RejectedFrame>{} : it->second.rejected;
}

std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> Registry::frames(const std::string& run_id) const {
  std::lock_guard lock(mutex_);
  const auto it = runs_.find(run_id);
  if (it == runs_.end()) return std::nullopt;
  std::vector<std::shared_ptr<const AnalyzedFrame>> out;
  out.reserve(it->second.committed.size());
  for (const auto& [index, frame] : it->second.committed) out.push_back(frame);
  return out;
}

std::shared_ptr<const AnalyzedFrame> Registry::row(const std::string& run_id, std::uint32_t index) const {
  std::lock_guard lock(mutex_);
  const auto it = runs_.find(run_id);
  if (it == runs_.end()) return nullptr;
  const auto f = it->second.committed.find(index);
  return f == it->second.committed.end() ? nullptr : f->second;
}

std::shared_ptr<const AnalyzedFrame> Registry::frame(const std::string& run_id, std::uint32_t index) const {
  std::shared_ptr<const AnalyzedFrame> row;
  std::shared_ptr<RunStore> store;
  {
    std::lock_guard lock(mutex_);
    const auto it = runs_.find(run_id);
    if (it == runs_.end()) return nullptr;
    const auto f = it->second.committed.find(index);
    if (f == it->second.committed.end()) return nullptr;
    row = f->second;
    store = it->second.store;
  }
  if (auto cached = cache_.diagrams(run_id, index)) return cached;
  auto full = std::make_shared<AnalyzedFrame>(*row);
  try {
    full->diagrams = store->diagrams(index);  // off the registry's lock
  } catch (const std::exception& e) {
    throw DiagramsUnavailable("run " + run_id + " frame " + std::to_string(index) +
                              ": its diagrams cannot be read from the store: " + e.what());
  }
  cache_.keep(run_id, index, full);
  return full;
}

Frame Registry::network(const std::string& run_id, std::uint32_t index) const {
  const std::string what = "run " + run_id + " frame " + std::to_string(index);
  std::shared_ptr<RunStore> store;
  {
    std::lock_guard lock(mutex_);
    const auto it = runs_.find(run_id);
    if (it == runs_.end() || !it->second.committed.count(index))
      throw NetworkUnavailable(what + ": no such analyzed frame");
    store = it->second.store;
  }
  if (const auto cached = cache_.network(run_id, index)) return *cached;
  std::optional<Frame> network;
  try {
    network = store->network(index);  // off the registry's lock
  } catch (const std::exception& e) {
    throw NetworkUnavailable(what + ": the force network is not stored: " + e.what());
  }
  if (!network)
    throw NetworkUnavailable(what + ": the force network is not stored: the frame was analyzed before the store " +
                             "kept networks (it came from a " + kStoreSchemaV1 + " store); analyze the run again " +
                             "(fnet-analyze store) to have it");
  auto kept = std::make_shared<const Frame>(std::move(*network));
  cache_.keep(run_id, index, kept);
  return *kept;
}

std::string Registry::newest_run() const {
  std::lock_guard lock(mutex_);
  // A run whose activity is unknown (a store from before the times were kept) is the oldest.
  const Run* newest = nullptr;
  for (const auto& [id, run] : runs_)
    if (!newest || run.last_activity > newest->last_activity) newest = &run;
  return newest ? newest->run_id : std::string();
}

std::vector<Registry::MemberRun> Registry::ensemble_members(const std::string& ensemble) const {
  std::vector<MemberRun> out;
  if (ensemble.empty()) return out;
  std::lock_guard lock(mutex_);
  for (const auto& [id, run] : runs_) {
    if (!run.has_info || run.info.ensemble != ensemble) continue;
    MemberRun& m = out.emplace_back(MemberRun{id, {}});
    m.frames.reserve(run.committed.size());
    for (const auto& [index, frame] : run.committed) m.frames.push_back(frame);
  }
  return out;
}

std::uint64_t Registry::subscribe(const std::string& run_id, std::optional<std::uint32_t> since,
                                  std::shared_ptr<Subscriber> subscriber) {
  return locked_then_deliver([&] {
    const std::uint64_t id = next_subscription_++;
    auto outbox = std::make_shared<Outbox>();
    outbox->id = id;
    outbox->run_id = run_id;
    outbox->subscriber = std::move(subscriber);
    // `since` skips the points of the frames committed so far up to it; every later commit has a
    // higher index and is delivered, as is every frame of a run that appears later.
    if (since)
      for (const auto& [rid, run] : runs_)
        if ((run_id.empty() || rid == run_id) && !run.committed.empty())
          outbox->delivered[rid] = std::min(*since, run.committed.rbegin()->first);
    mark_locked(outbox);  // the points committed before
    subscriptions_[id] = std::move(outbox);
    return id;
  });
}

void Registry::unsubscribe(std::uint64_t id) {
  std::shared_ptr<Outbox> outbox;
  {
    std::lock_guard lock(mutex_);
    const auto it = subscriptions_.find(id);
    if (it == subscriptions_.end()) return;
    outbox = std::move(it->second);
    subscriptions_.erase(it);
  }
  // A point being delivered at this moment may still arrive; none after it.
  std::lock_guard lock(outbox->mutex);
  outbox->ended = true;
}

std::size_t Registry::subscriptions() const {
  std::lock_guard lock(mutex_);
  return subscriptions_.size();
}

Counters Registry::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

std::deque<std::string> Registry::recent_rejections() const {
  std::lock_guard lock(mutex_);
  return recent_rejections_;
}

double Registry::frames_per_second() const {
  std::lock_guard lock(mutex_);
  const auto horizon = Clock::now() - std::chrono::seconds(10);
  std::size_t n = 0;
  for (const auto& t : recent_commits_) n += t >= horizon;
  return static_cast<double>(n) / 10.0;
}

double Registry::oldest_pending_seconds() const {
  std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  double oldest = 0;
  for (const auto& [id, run] : runs_)
    if (const auto arrived = run.pipeline.oldest_arrival())
      oldest = std::max(oldest, std::chrono::duration<double>(now - *arrived).count());
  return oldest;
}

}  // namespace fnet::server
