// The registry as the queries read it (server/query/frame_lookup.hpp).
#pragma once

#include "server/query/frame_lookup.hpp"
#include "server/registry/run_registry.hpp"

namespace fnet::server {

class RegistryFrames final : public query::FrameLookup {
 public:
  explicit RegistryFrames(const Registry& registry) : registry_(registry) {}

  // Read back from the run's store through the registry's cache; a store that cannot be read is
  // the registry's DiagramsUnavailable (an internal error to the client).
  std::shared_ptr<const AnalyzedFrame> frame(const std::string& run, std::uint32_t index) const override;
  std::shared_ptr<const AnalyzedFrame> row(const std::string& run, std::uint32_t index) const override;
  std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> frames(const std::string& run) const override;
  // Read back from the run's store; query::NoNetwork when the store does not hold it.
  Frame network(const std::string& run, std::uint32_t index) const override;
  std::vector<query::MemberRun> ensemble_members(const std::string& ensemble) const override;

 private:
  const Registry& registry_;
};

}  // namespace fnet::server
