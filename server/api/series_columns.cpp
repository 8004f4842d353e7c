#include "server/api/series_columns.hpp"

#include <string>

#include "server/api/api_params.hpp"

namespace fnet::server {

FrameRange get_frame_range(const json& params) {
  FrameRange r{get_index(params, "from"), get_index(params, "to")};
  if (r.from && r.to && *r.from > *r.to)
    invalid("from", "parameter 'from' (" + std::to_string(*r.from) + ") is after 'to' (" + std::to_string(*r.to) +
                        "): the range is inclusive, from <= to");
  return r;
}

void SeriesColumns::add(const AnalyzedFrame& f, json value, bool infinite) {
  frame_.push_back(f.header.index);
  step_.push_back(f.header.step);
  time_.push_back(f.header.time);
  rho_.push_back(f.header.rho);
  z_.push_back(f.header.z);
  previous_.push_back(f.previous ? json(*f.previous) : json(nullptr));
  value_.push_back(std::move(value));
  infinite_.push_back(infinite);
  any_infinite_ |= infinite;
}

void SeriesColumns::put(json& out) const {
  out["frame"] = frame_;
  out["step"] = step_;
  out["time"] = time_;
  out["rho"] = rho_;
  out["z"] = z_;
  out["value"] = value_;
  out["previous"] = previous_;
  if (any_infinite_) out["infinite"] = infinite_;
}

}  // namespace fnet::server
