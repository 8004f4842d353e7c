#include "server/analysis/ingest.hpp"

#include <chrono>
#include <iostream>

#include "common/transport/frame_transport.hpp"

namespace fnet::server {

Ingest::Ingest(Registry& registry, IngestOptions options)
    : registry_(registry), options_(options), thread_([this] { run(); }) {}

Ingest::~Ingest() { stop(); }

void Ingest::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

void Ingest::run() {
  try {
    dds::FrameSubscriber subscriber(options_.domain, static_cast<std::int32_t>(options_.max_in_flight));
    auto last_gap_check = std::chrono::steady_clock::now();
    while (!stopping_) {
      const std::size_t in_flight = registry_.in_flight();
      if (in_flight >= options_.max_in_flight) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      } else {
        dds::Received got = subscriber.take(DDS_MSECS(100), options_.max_in_flight - in_flight);
        for (const RunInfo& info : got.infos) registry_.on_info(info);
        for (RunFrame& frame : got.frames) registry_.on_frame(std::move(frame));
        for (const std::string& reason : got.malformed) registry_.on_malformed(reason);
      }
      if (std::chrono::steady_clock::now() - last_gap_check > std::chrono::seconds(1)) {
        registry_.check_gaps();
        last_gap_check = std::chrono::steady_clock::now();
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "fnet-server: DDS ingest stopped: " << e.what() << "\n";
  }
}

}  // namespace fnet::server
