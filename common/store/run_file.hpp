// The HDF5 run file that fnet-simd --out writes: a run's parameters (root attributes) and every
// frame, appended to flat extendible datasets in SWMR mode, so that the file can be read
// (read_run_file, or h5py with swmr=True) while it is written, and a killed writer leaves every
// frame committed before the kill. Schema: proto/run_file.md.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/run/run_frame.hpp"
#include "common/store/hdf5_handle.hpp"
#include "common/store/provenance_attributes.hpp"

namespace fnet {

inline constexpr const char* kRunFileSchema = "fnet-run-3";
// Before 3D frames: still read, as 2D frames.
inline constexpr const char* kRunFileSchemaV2 = "fnet-run-2";

class RunFileWriter {
 public:
  // Creates `path` (replacing any file there) and records the run's parameters.
  RunFileWriter(const std::filesystem::path& path, const RunInfo& info);
  // Continues a file written earlier (resuming a run): its frames with index < `keep` are copied
  // into a fresh file that replaces it, so a resumed run can write the others again.
  static RunFileWriter reopen(const std::filesystem::path& path, std::uint32_t keep);

  void append(const RunFrame& frame);
  std::size_t frames() const { return frames_; }

 private:
  RunFileWriter() = default;
  void create(const std::filesystem::path& path, const RunInfo& info);
  hid_t set(const char* name) const;
  h5::File file_;
  std::map<std::string, h5::Dataset> sets_;  // declared after file_: closed before it
  std::size_t frames_ = 0;
};

struct RunFileContents {
  RunInfo info;
  std::vector<RunFrame> frames;  // the committed frames, in the order written
  FileProvenance provenance;     // which fnet wrote the file, and when ("unknown" for fnet-run-1)
};

// Reads a whole run file, also one still being written; throws h5::Error naming the file and
// what is missing or malformed.
RunFileContents read_run_file(const std::filesystem::path& path);

// The run's parameters as root attributes.
void write_run_info(hid_t root, const RunInfo& info);
RunInfo read_run_info(hid_t root, const std::string& where);

}  // namespace fnet
