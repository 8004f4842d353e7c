// Run files of schema fnet-run-1, which fnet-simd wrote before the run file became readable while
// it is written: one group /frames/NNNNNN per frame. Read only; resuming such a run writes the
// current schema.
#pragma once

#include <string>

#include "common/store/hdf5_handle.hpp"
#include "common/store/run_file.hpp"

namespace fnet {

inline constexpr const char* kRunFileSchemaV1 = "fnet-run-1";

// `file` is open read-only; `where` names it in errors.
RunFileContents read_run_file_v1(hid_t file, const std::string& where);

}  // namespace fnet
