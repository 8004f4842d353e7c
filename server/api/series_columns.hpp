// What series.get answers with, with or without `ratio`: the frames in 'from'..'to' and their
// equal-length arrays (proto/api.md, series.get).
#pragma once

#include <cstdint>
#include <optional>

#include <nlohmann/json.hpp>

#include "common/analysis/analyzed_frame.hpp"
#include "common/analysis/step_series.hpp"

namespace fnet::server {

// 'from' and 'to', inclusive, each optional; error -32602 on 'from' when from > to.
FrameRange get_frame_range(const nlohmann::json& params);

// frame, step, time, rho, z, previous and value, one entry per frame added; `infinite` too, put
// only when some value is infinite (its value then null).
class SeriesColumns {
 public:
  void add(const AnalyzedFrame& f, nlohmann::json value, bool infinite);
  void put(nlohmann::json& out) const;

 private:
  nlohmann::json frame_ = nlohmann::json::array(), step_ = nlohmann::json::array(), time_ = nlohmann::json::array(),
                 rho_ = nlohmann::json::array(), z_ = nlohmann::json::array(), value_ = nlohmann::json::array(),
                 previous_ = nlohmann::json::array(), infinite_ = nlohmann::json::array();
  bool any_infinite_ = false;
};

}  // namespace fnet::server
