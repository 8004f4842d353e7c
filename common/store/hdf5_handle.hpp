// RAII ownership of HDF5 identifiers: each kind of hid_t closed by its own H5?close.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include <hdf5.h>

namespace fnet::h5 {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The operating system's word for why the HDF5 call that just failed failed ("No space left on
// device", "Too many open files"), from HDF5's error stack, as " (cause)"; empty when the stack
// names none. Call before any other HDF5 call: each clears the stack.
std::string system_cause();

template <herr_t (*Close)(hid_t)>
class Handle {
 public:
  Handle() = default;
  // Takes ownership of `id`; throws naming `what` when the call that produced it failed.
  Handle(hid_t id, const std::string& what) : id_(id) {
    if (id_ < 0) throw Error("HDF5: " + what + " failed" + system_cause());
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  ~Handle() { close(); }
  hid_t get() const { return id_; }

 private:
  void close() {
    if (id_ >= 0) Close(id_);
    id_ = H5I_INVALID_HID;
  }
  hid_t id_ = H5I_INVALID_HID;
};

using File = Handle<H5Fclose>;
using Group = Handle<H5Gclose>;
using Dataset = Handle<H5Dclose>;
using Dataspace = Handle<H5Sclose>;
using Attribute = Handle<H5Aclose>;
using Datatype = Handle<H5Tclose>;
using PropertyList = Handle<H5Pclose>;

inline void check(herr_t rc, const std::string& what) {
  if (rc < 0) throw Error("HDF5: " + what + " failed" + system_cause());
}

}  // namespace fnet::h5
