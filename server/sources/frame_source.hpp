// One interface for every input of frames: a recorded run (a run file, a CSV folder), one frame's
// files, and inputs still being written while they are read. A command reads any of them the same
// way: the announcement first, then the frames one by one, in the input's order.
#pragma once

#include <optional>

#include "common/run/run_frame.hpp"

namespace fnet::sources {

class FrameSource {
 public:
  FrameSource() = default;
  FrameSource(const FrameSource&) = delete;
  FrameSource& operator=(const FrameSource&) = delete;
  virtual ~FrameSource() = default;

  // The run's announcement as the input records it. An input that records none announces what it
  // knows: no run id (the command line names the run), config_json "{}", the number of frames it
  // lists (0 where it cannot know ahead) and the first frame's particle count.
  virtual const RunInfo& announcement() const = 0;

  // The next frame, std::nullopt once the input has ended (and at every call after). A source that
  // follows an input still being written blocks until its next frame is complete or the input
  // ends. Frames are not validated here. Input that cannot be read throws an exception whose
  // message begins with the file at fault, and the line for a text file ("PATH:LINE: what").
  virtual std::optional<RunFrame> next() = 0;
};

// The next frame of an input that must hold one; an input that has ended throws.
RunFrame next_frame(FrameSource& source);

}  // namespace fnet::sources
