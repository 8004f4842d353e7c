#include "server/registry/run_store.hpp"

#include <iostream>
#include <stdexcept>
#include <type_traits>

namespace fnet::server {

RunStore::RunStore(std::filesystem::path path, std::string run_id)
    : path_(std::move(path)), run_id_(std::move(run_id)) {}

void RunStore::push(Record record, StoreTime at) {
  std::lock_guard lock(queue_mutex_);
  if (!problem_.empty()) return;  // the store stopped taking writes
  queue_.push_back({std::move(record), at});
}

void RunStore::queue(const RunInfo& info, StoreTime at) { push(info, at); }
void RunStore::queue(std::shared_ptr<const AnalyzedFrame> frame, StoreTime at) { push(std::move(frame), at); }
void RunStore::queue(const RejectedFrame& rejected, StoreTime at) { push(rejected, at); }

void RunStore::write_queued() {
  std::lock_guard io(io_mutex_);
  write_queued_locked();
}

void RunStore::fail_locked(const std::string& what) {
  failed_ = true;
  std::cerr << "fnet-server: store of run " << run_id_ << ": " << what << "\n";
  std::lock_guard lock(queue_mutex_);
  problem_ = what;
  queue_.clear();
}

void RunStore::write_queued_locked() {
  while (true) {
    Queued next;
    {
      std::lock_guard lock(queue_mutex_);
      if (queue_.empty()) return;
      next = std::move(queue_.front());
      queue_.pop_front();
    }
    if (failed_) continue;
    try {
      if (!writer_) writer_ = std::make_unique<StoreWriter>(path_, run_id_);
      std::visit(
          [&](const auto& r) {
            using R = std::decay_t<decltype(r)>;
            if constexpr (std::is_same_v<R, RunInfo>)
              writer_->write_info(r, next.at);
            else if constexpr (std::is_same_v<R, RejectedFrame>)
              writer_->append(r, next.at);
            else
              writer_->append(*r, next.at);
          },
          next.record);
    } catch (const std::exception& e) {
      fail_locked(e.what());
    }
  }
}

std::optional<Frame> RunStore::network(std::uint32_t index) {
  std::lock_guard io(io_mutex_);
  write_queued_locked();
  const std::string why = problem();
  if (!writer_ && failed_) throw std::runtime_error("the run has no store (" + why + ")");
  try {
    // A run loaded from its store and not written since is read without rewriting the file.
    return writer_ ? writer_->network(index) : read_network(path_, index);
  } catch (const std::exception& e) {
    std::string message = e.what();
    if (!why.empty()) message += " (" + why + ")";
    throw std::runtime_error(message);
  }
}

std::string RunStore::problem() const {
  std::lock_guard lock(queue_mutex_);
  return problem_;
}

}  // namespace fnet::server
