#include "server/sources/frame_source.hpp"

#include <stdexcept>

namespace fnet::sources {

RunFrame next_frame(FrameSource& source) {
  std::optional<RunFrame> frame = source.next();
  if (!frame) throw std::runtime_error("the input holds no frame");
  return std::move(*frame);
}

}  // namespace fnet::sources
