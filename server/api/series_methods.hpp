// series.get: a run's distances between consecutive frames, or their ratio d_B / d_Wq, frame by
// frame (proto/api.md).
#pragma once

#include "server/api/method.hpp"

namespace fnet::server {

Method series_get_method(const Registry& registry);

}  // namespace fnet::server
