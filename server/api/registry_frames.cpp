#include "server/api/registry_frames.hpp"

#include "server/query/query_errors.hpp"

namespace fnet::server {

std::shared_ptr<const AnalyzedFrame> RegistryFrames::frame(const std::string& run, std::uint32_t index) const {
  return registry_.frame(run, index);
}

std::shared_ptr<const AnalyzedFrame> RegistryFrames::row(const std::string& run, std::uint32_t index) const {
  return registry_.row(run, index);
}

std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> RegistryFrames::frames(const std::string& run) const {
  return registry_.frames(run);
}

Frame RegistryFrames::network(const std::string& run, std::uint32_t index) const {
  try {
    return registry_.network(run, index);
  } catch (const NetworkUnavailable& e) {
    throw query::NoNetwork(run, index, e.what());
  }
}

std::vector<query::MemberRun> RegistryFrames::ensemble_members(const std::string& ensemble) const {
  std::vector<query::MemberRun> out;
  for (Registry::MemberRun& m : registry_.ensemble_members(ensemble))
    out.push_back({std::move(m.run_id), std::move(m.frames)});
  return out;
}

}  // namespace fnet::server
