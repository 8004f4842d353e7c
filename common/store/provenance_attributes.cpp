#include "common/store/provenance_attributes.hpp"

#include "common/build_info/build_info.hpp"
#include "common/store/hdf5_io.hpp"

namespace fnet {

void write_provenance(hid_t root) {
  const BuildInfo b = build_info();
  h5::write_attribute(root, "fnet_version", std::string(b.version));
  h5::write_attribute(root, "fnet_commit", std::string(b.commit));
  h5::write_attribute(root, "created", utc_timestamp());
}

FileProvenance read_provenance(hid_t root, const std::string& where) {
  FileProvenance p;
  const auto read = [&](const char* name, std::string& out) {
    if (H5Aexists(root, name) > 0) out = h5::read_string(root, name, where);
  };
  read("fnet_version", p.fnet_version);
  read("fnet_commit", p.fnet_commit);
  read("created", p.created);
  return p;
}

}  // namespace fnet
