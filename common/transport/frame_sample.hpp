// A ForceFrame sample as DDS hands it over (the IDL's C struct, proto/fnet.idl) turned into a
// RunFrame. Only what the struct itself can get wrong is checked here: arrays whose lengths
// disagree, a dimension other than 2 or 3, a particle table of the wrong length; the frame is
// validated by the analysis (validate(), common/topology/frame.hpp).
#pragma once

#include "common/run/run_frame.hpp"
#include "fnet.h"

namespace fnet::dds {

// Throws FrameError naming the run, the frame and what disagrees.
RunFrame decode_frame_sample(const fnet_ForceFrame& sample);

}  // namespace fnet::dds
