#include "server/registry/run_store.hpp"

#include <iostream>
#include <stdexcept>
#include <type_traits>

#include "common/store/hdf5_io.hpp"

namespace fnet::server {

RunStore::RunStore(std::filesystem::path path, std::string run_id, std::shared_ptr<StoreChecker> checker)
    : path_(std::move(path)), run_id_(std::move(run_id)), checker_(std::move(checker)) {}

void RunStore::push(Record record, StoreTime at) {
  std::lock_guard lock(queue_mutex_);
  queue_.push_back({std::move(record), at});
}

void RunStore::queue(const RunInfo& info, StoreTime at) { push(info, at); }
void RunStore::queue(std::shared_ptr<const AnalyzedFrame> frame, StoreTime at) { push(std::move(frame), at); }
void RunStore::queue(const RejectedFrame& rejected, StoreTime at) { push(rejected, at); }

void RunStore::write_queued() {
  std::lock_guard io(io_mutex_);
  write_queued_locked(false);
}

bool RunStore::retry() {
  std::lock_guard io(io_mutex_);
  // Continuing the store copies it: on a disk without room for the copy an attempt would fail
  // again (and each failed HDF5 file leaves some of HDF5's memory behind), so it waits for room.
  std::error_code no_size, no_space;
  const auto size = std::filesystem::file_size(path_, no_size);
  const auto space = std::filesystem::space(path_.parent_path(), no_space);
  constexpr std::uintmax_t kMargin = 1 << 20;
  if (!no_space && space.available < (no_size ? 0 : size) + kMargin) return false;
  write_queued_locked(true);
  return fault().empty();
}

std::vector<RunStore::Record> RunStore::take_written() {
  std::lock_guard lock(queue_mutex_);
  return std::exchange(written_, {});
}

bool RunStore::holds_locked(const Record& record) const {
  if (const auto* frame = std::get_if<std::shared_ptr<const AnalyzedFrame>>(&record))
    return writer_->holds_frame((*frame)->header.index);
  if (const auto* rejected = std::get_if<RejectedFrame>(&record)) return writer_->holds_rejection(rejected->index);
  return false;  // an announcement written twice is only a repeated row of the announcements
}

void RunStore::write_queued_locked(bool retrying) {
  h5::quiet();  // on this thread too: the exceptions carry HDF5's messages
  bool reopened = false;
  while (true) {
    const Queued* head = nullptr;
    {
      std::lock_guard lock(queue_mutex_);
      if (queue_.empty() || sealed_ || (!fault_.empty() && !retrying)) return;
      head = &queue_.front();  // only this thread pops, under io_mutex_: the head stays put
    }
    try {
      if (!writer_) {
        // A file this process did not write is read by StoreWriter to be continued: checked first.
        if (checker_ && !written_here_)
          if (const std::string refused = checker_->refusals({path_}).front(); !refused.empty())
            throw std::runtime_error("cannot continue the store: " + refused);
        writer_ = std::make_unique<StoreWriter>(path_, run_id_);
        written_here_ = true;
        reopened = true;
        std::lock_guard lock(queue_mutex_);
        open_ = true;
      }
      if (!reopened || !holds_locked(head->record))
        std::visit(
            [&](const auto& r) {
              using R = std::decay_t<decltype(r)>;
              if constexpr (std::is_same_v<R, RunInfo>)
                writer_->write_info(r, head->at);
              else if constexpr (std::is_same_v<R, RejectedFrame>)
                writer_->append(r, head->at);
              else
                writer_->append(*r, head->at);
            },
            head->record);
    } catch (const std::exception& e) {
      // The file may hold part of the record: it is closed, and continued from what it commits.
      writer_.reset();
      std::lock_guard lock(queue_mutex_);
      if (fault_.empty())
        std::cerr << "fnet-server: store of run " << run_id_ << ": " << e.what() << "; " << queue_.size()
                  << " record(s) wait, retried periodically\n";
      fault_ = e.what();
      open_ = false;
      return;
    }
    std::lock_guard lock(queue_mutex_);
    if (!fault_.empty()) {
      std::cerr << "fnet-server: store of run " << run_id_ << " takes writes again\n";
      fault_.clear();
    }
    written_.push_back(std::move(queue_.front().record));
    queue_.pop_front();
  }
}

bool RunStore::close(bool seal) {
  std::lock_guard io(io_mutex_);
  std::lock_guard lock(queue_mutex_);
  if (seal) sealed_ = true;
  if (!queue_.empty() && !seal) return false;
  h5::quiet();
  writer_.reset();
  open_ = false;
  return true;
}

template <class Read>
auto RunStore::read_locked(Read&& read) {
  write_queued_locked(false);
  const std::string why = fault();
  try {
    return read(writer_.get());
  } catch (const std::exception& e) {
    std::string message = e.what();
    if (!why.empty()) message += " (the store does not take writes: " + why + ")";
    throw std::runtime_error(message);
  }
}

std::optional<Frame> RunStore::network(std::uint32_t index) {
  std::lock_guard io(io_mutex_);
  // A closed store is read without reopening it for writing.
  return read_locked([&](const StoreWriter* w) { return w ? w->network(index) : read_network(path_, index); });
}

FrameDiagramSet RunStore::diagrams(std::uint32_t index) {
  std::lock_guard io(io_mutex_);
  return read_locked([&](const StoreWriter* w) { return w ? w->diagrams(index) : read_diagrams(path_, index); });
}

std::string RunStore::fault() const {
  std::lock_guard lock(queue_mutex_);
  return fault_;
}

bool RunStore::open() const {
  std::lock_guard lock(queue_mutex_);
  return open_;
}

}  // namespace fnet::server
