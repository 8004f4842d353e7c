// The HDF5 run file: a run's parameters and every frame, appended as the run goes and flushed
// after each frame so that a killed writer leaves a readable file. Schema: proto/run_file.md.
#pragma once

#include <filesystem>
#include <vector>

#include "common/analysis/run_frame.hpp"
#include "common/store/hdf5_handle.hpp"

namespace fnet {

inline constexpr const char* kRunFileSchema = "fnet-run-1";

class RunFileWriter {
 public:
  // Creates `path` (replacing any file there) and records the run's parameters.
  RunFileWriter(const std::filesystem::path& path, const RunInfo& info);
  // Reopens a file written earlier to append to it (resuming a run): frames with index >= `keep`
  // are removed first, so a resumed run can rewrite them.
  static RunFileWriter reopen(const std::filesystem::path& path, std::uint32_t keep);

  void append(const RunFrame& frame);
  std::size_t frames() const { return frames_; }

 private:
  RunFileWriter() = default;
  h5::File file_;
  std::size_t frames_ = 0;
};

struct RunFileContents {
  RunInfo info;
  std::vector<RunFrame> frames;  // in frame order
};

// Reads a whole run file; throws h5::Error naming the file and what is missing or malformed.
RunFileContents read_run_file(const std::filesystem::path& path);

// Shared with the analysis store, which records the same run parameters and frame headers.
void write_run_info(hid_t root, const RunInfo& info);
RunInfo read_run_info(hid_t root, const std::string& where);
void write_frame_header(hid_t group, const FrameHeader& header);
FrameHeader read_frame_header(hid_t group, const std::string& run_id, const std::string& where);

}  // namespace fnet
