// Building hand-written frames in one line.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet::testing {

// A frame of n particles (no particle table) with the given contacts.
inline Frame frame_of(std::size_t n, std::vector<Contact> contacts, std::string label = "test frame") {
  Frame frame;
  frame.label = std::move(label);
  frame.particle_count = n;
  frame.contacts = std::move(contacts);
  return frame;
}

// The same force as normal and tangential, so one expectation checks both networks.
inline Contact both(std::int64_t i, std::int64_t j, double force) { return {i, j, force, force}; }

}  // namespace fnet::testing
