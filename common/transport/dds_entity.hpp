// RAII ownership of a Cyclone DDS entity handle (participant, topic, reader, writer, waitset...).
// Deleting a participant deletes its children, so children may be held without ownership.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include <dds/dds.h>

namespace fnet::dds {

class Error : public std::runtime_error {
 public:
  Error(const std::string& what, dds_return_t rc) : std::runtime_error(what + ": " + dds_strretcode(rc)), code_(rc) {}
  dds_return_t code() const { return code_; }

 private:
  dds_return_t code_;
};

// Returns `handle` if it is a valid entity, else throws naming the call that made it.
inline dds_entity_t check(dds_entity_t handle, const char* what) {
  if (handle < 0) throw Error(what, handle);
  return handle;
}

class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  Entity& operator=(Entity&& other) noexcept {
    if (this != &other) reset(std::exchange(other.handle_, 0));
    return *this;
  }
  ~Entity() { reset(); }

  dds_entity_t get() const { return handle_; }
  explicit operator bool() const { return handle_ > 0; }
  void reset(dds_entity_t handle = 0) {
    if (handle_ > 0) dds_delete(handle_);
    handle_ = handle;
  }

 private:
  dds_entity_t handle_ = 0;
};

class Qos {
 public:
  Qos() : qos_(dds_create_qos()) {}
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  ~Qos() { dds_delete_qos(qos_); }
  dds_qos_t* get() const { return qos_; }

 private:
  dds_qos_t* qos_;
};

}  // namespace fnet::dds
