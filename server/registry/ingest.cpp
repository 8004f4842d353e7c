#include "server/registry/ingest.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

namespace fnet::server {
namespace {

std::unique_ptr<dds::FrameSubscriber> subscribe(const IngestOptions& options) {
  try {
    return std::make_unique<dds::FrameSubscriber>(
        options.domain, static_cast<std::int32_t>(reader_frames(options)),
        dds::FrameSizeBound{options.max_frame_bytes, "the bound on one frame (fnet-server --max-frame-mib)"});
  } catch (const std::exception& e) {
    const char* uri = std::getenv("CYCLONEDDS_URI");
    throw std::runtime_error("cannot subscribe to DDS domain " + std::to_string(options.domain) + " (" + e.what() +
                             "); CYCLONEDDS_URI is " + (uri ? "'" + std::string(uri) + "'" : std::string("not set")) +
                             ": check that it names a readable, valid Cyclone DDS configuration");
  }
}

}  // namespace

std::size_t reader_frames(const IngestOptions& o) {
  const std::size_t fit = o.max_in_flight_bytes / std::max<std::size_t>(o.max_frame_bytes, 1);
  return std::clamp<std::size_t>(fit, 1, std::max<std::size_t>(o.max_in_flight, 1));
}

Ingest::Ingest(Registry& registry, IngestOptions options)
    : registry_(registry), options_(options), subscriber_(subscribe(options_)), thread_([this] { run(); }) {}

Ingest::~Ingest() { stop(); }

void Ingest::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

std::string Ingest::state() const {
  std::lock_guard lock(mutex_);
  return state_;
}

void Ingest::run() {
  try {
    auto last_gap_check = std::chrono::steady_clock::now();
    while (!stopping_) {
      const std::size_t in_flight = registry_.in_flight(), bytes = registry_.in_flight_bytes();
      if (in_flight >= options_.max_in_flight || bytes >= options_.max_in_flight_bytes) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      } else {
        dds::Received got =
            subscriber_->take(DDS_MSECS(100), options_.max_in_flight - in_flight, options_.max_in_flight_bytes - bytes);
        for (const RunInfo& info : got.infos) registry_.on_info(info);
        for (RunFrame& frame : got.frames) registry_.on_frame(std::move(frame));
        for (const dds::RefusedFrame& r : got.refused) registry_.on_refused(r.header, r.reason);
        for (const std::string& reason : got.malformed) registry_.on_malformed(reason);
      }
      if (std::chrono::steady_clock::now() - last_gap_check > std::chrono::seconds(1)) {
        registry_.check_gaps();
        last_gap_check = std::chrono::steady_clock::now();
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "fnet-server: DDS ingest stopped: " << e.what() << "; the API serves only what was stored\n";
    std::lock_guard lock(mutex_);
    state_ = std::string("stopped: ") + e.what();
  }
}

}  // namespace fnet::server
