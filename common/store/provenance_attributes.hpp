// Which fnet wrote an HDF5 file, and when: root attributes of every store and run file, so that a
// result found on disk names the software that made it. Files written before these attributes
// existed read back as "unknown".
#pragma once

#include <string>

#include "common/store/hdf5_handle.hpp"

namespace fnet {

struct FileProvenance {
  std::string fnet_version = "unknown";  // `fnet_version`: the writer's version
  std::string fnet_commit = "unknown";   // `fnet_commit`: the git commit the writer was built from
  std::string created = "unknown";       // `created`: when this file was written, ISO 8601 UTC
};

// Writes this build's version and commit and the current time as the root attributes above.
void write_provenance(hid_t root);
FileProvenance read_provenance(hid_t root, const std::string& where);

}  // namespace fnet
