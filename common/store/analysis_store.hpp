// The analysis store: one HDF5 file per run holding its parameters, every analyzed frame's
// diagrams, its force network and the distances to the previous accepted frame, and the rejected
// frames with their reasons. Appended frame by frame by fnet-server, or offline by fnet-analyze store; read back on
// restart. Schema: proto/store.md.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/analysis/analyzed_frame.hpp"
#include "common/run/run_frame.hpp"
#include "common/store/hdf5_handle.hpp"
#include "common/store/provenance_attributes.hpp"

namespace fnet {

inline constexpr const char* kStoreSchema = "fnet-store-3";
// The convention for classes that never die under which the stored distances are measured.
inline constexpr const char* kStoreConvention = "floor";
// The first schema, without the frames' networks: still read, and continued as the current one.
inline constexpr const char* kStoreSchemaV1 = "fnet-store-1";
// Before 3D frames: still read (its networks as 2D frames), and continued as the current one.
inline constexpr const char* kStoreSchemaV2 = "fnet-store-2";

// When something was written to a store: seconds since the Unix epoch (UTC), NaN for a record
// of a store written before the time was kept.
using StoreTime = double;
StoreTime store_time_now();

struct StoredRun {
  RunInfo info;
  bool has_info = false;                // false until the run's announcement was seen
  StoreTime announced_at = NAN;         // when the last announcement was written
  std::string schema;                   // the schema the file was written in
  FileProvenance provenance;            // which fnet wrote the file, and when
  std::vector<AnalyzedFrame> frames;    // ascending index; their networks are not read (read_network)
  std::vector<bool> has_network;        // per frame: whether its force network is stored
  std::vector<StoreTime> committed_at;  // when each frame was committed
  std::vector<RejectedFrame> rejected;
  std::vector<StoreTime> rejected_at;  // when each frame was rejected
  // The run's last activity the store knows of: the latest of those times (none if none known).
  std::optional<StoreTime> last_activity() const;
};

// Appends to a run's store in SWMR mode, so that the file stays readable (with read_store, or
// h5py with swmr=True) while it is written and after the writer is killed.
class StoreWriter {
 public:
  // Creates the store, or continues an existing one: its committed content is copied into a
  // fresh file that replaces it (a store left by a killed writer cannot be reopened for writing).
  // A failure (a full disk, no file descriptor left) leaves the store as it was and removes
  // the fresh file.
  StoreWriter(const std::filesystem::path& path, const std::string& run_id);
  void write_info(const RunInfo& info, StoreTime at = store_time_now());
  void append(const AnalyzedFrame& frame, StoreTime at = store_time_now());
  void append(const RejectedFrame& rejected, StoreTime at = store_time_now());
  // The force network of committed frame `index`, read back from the file; nullopt when the frame
  // was committed without one (copied from a fnet-store-1 store). Throws h5::Error for a frame the
  // store does not hold.
  std::optional<Frame> network(std::uint32_t index) const;
  // The diagrams (points and counts) of committed frame `index`, read back from the file. Throws
  // h5::Error for a frame the store does not hold.
  FrameDiagramSet diagrams(std::uint32_t index) const;
  // Whether the file holds frame `index` committed, or its rejection.
  bool holds_frame(std::uint32_t index) const;
  bool holds_rejection(std::uint32_t index) const;

 private:
  void create(const std::filesystem::path& path, const std::filesystem::path& fresh);
  hid_t set(const char* name) const;
  h5::File file_;
  std::string run_id_;
  std::vector<std::uint32_t> frames_;        // committed frame indices, ascending: the row of each
  std::vector<std::uint32_t> rejected_;      // rejected frame indices, in the order written
  std::map<std::string, h5::Dataset> sets_;  // declared after file_: closed before it
};

// Throws h5::Error naming the file and what is missing or malformed: anything but a regular file,
// a run id that is not a valid one (run_names.hpp), any committed row whose offsets, counts or
// frame indices break the schema's rules, a dataset larger than the file. Bounded in time: a
// corrupted file fails after kMetadataReadAttempts reads of its metadata.
StoredRun read_store(const std::filesystem::path& path);
// read_store for a store found in a data directory, which is written again under its run's name:
// the file must be named RUN.h5 after the run id it holds.
StoredRun read_store_in_data_dir(const std::filesystem::path& path);
// Reads a store found in a data directory as fnet-server serves it: read_store_in_data_dir, then
// the force network of every committed frame that has one, as read_network reads it (the file
// opened once). Throws as they do. What a store's check runs in a process of its own
// (server/registry/store_check.hpp), since HDF5 itself may never return on a damaged file.
void read_whole_store_in_data_dir(const std::filesystem::path& path);
// The force network of committed frame `index` of a store (opened read-only in SWMR mode: not
// for a store this process is writing, use StoreWriter::network); nullopt as StoreWriter::network.
std::optional<Frame> read_network(const std::filesystem::path& path, std::uint32_t index);
// The diagrams of committed frame `index` of a store, read alone (its frame column, then that
// frame's rows of counts, offsets and points), opened as read_network opens it. Throws h5::Error
// for a frame the store does not hold or whose rows break the schema's rules.
FrameDiagramSet read_diagrams(const std::filesystem::path& path, std::uint32_t index);

// Where a run's store lives in a data directory (run ids are restricted to [A-Za-z0-9._-]).
std::filesystem::path store_path(const std::filesystem::path& data_dir, const std::string& run_id);

}  // namespace fnet
