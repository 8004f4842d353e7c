// The outputs of fnet-simd beyond CSV: frames published on DDS (fnet_RunInfo, fnet_ForceFrame)
// and the HDF5 run file. Both take the shared RunFrame, which run_frame() makes once per snapshot.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <dds/dds.h>

#include "common/store/run_file.hpp"
#include "common/transport/frame_transport.hpp"
#include "server/dem/params.hpp"
#include "server/dem/snapshot.hpp"

namespace fnet::sim {

RunInfo run_info(const Params& params, const std::string& run_id, const std::string& ensemble = "");
RunFrame run_frame(const FrameSnapshot& snapshot);

// DIR/provenance.json beside a CSV export: which fnet wrote it and when (fnet_version,
// fnet_commit, created) and the run's announcement (`run`: parameters and seed, as run.get gives
// them), so that the folder names its origin wherever it is copied.
void write_csv_provenance(const std::filesystem::path& dir, const RunInfo& info);

// How the end of a run reached the DDS subscribers.
struct Delivery {
  bool acknowledged = true;        // every matched subscriber acknowledged every frame in time
  std::uint32_t lost_readers = 0;  // subscribers matched during the run and gone since
  dds::StoreOutcome stores;        // what the fnet-servers among them said of the run's store
};

// Publishes the run's announcement on construction and every frame handed to it.
class DdsSink {
 public:
  DdsSink(dds_domainid_t domain, const RunInfo& info);
  void operator()(const RunFrame& frame);
  // At the end of a run: waits (bounded) until every matched reader has every frame and every
  // fnet-server among them has them in its store (or reports a store fault), then keeps serving
  // late readers from the durability history for `linger` seconds.
  // Stops lingering early once should_stop() is true.
  Delivery finish(double ack_timeout_seconds, double linger_seconds, const std::function<bool()>& should_stop);
  // Whether any frame reader was matched at a frame's publication or during finish().
  bool reached_a_subscriber() const { return reached_; }
  bool subscriber_now() const { return publisher_.matched_readers() > 0; }

 private:
  dds::FramePublisher publisher_;
  std::string run_id_;
  std::uint32_t through_ = 0;  // one past the last frame index published
  bool reached_ = false;
};

// Appends every frame to the run file; on resume it reopens the file and drops frames from
// `first_frame` on, which the resumed run writes again.
class RunFileSink {
 public:
  RunFileSink(const std::filesystem::path& path, const RunInfo& info, bool resume, std::size_t first_frame);
  void operator()(const RunFrame& frame);

 private:
  std::unique_ptr<RunFileWriter> writer_;
};

}  // namespace fnet::sim
