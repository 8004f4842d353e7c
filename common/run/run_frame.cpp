#include "common/run/run_frame.hpp"

namespace fnet {

std::string frame_label(const std::string& run_id, std::uint32_t index) {
  return "run " + run_id + " frame " + std::to_string(index);
}

}  // namespace fnet
