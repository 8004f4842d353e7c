// A FrameLookup over frames held in memory, each analyzed as it is added: what a front end that
// read its frames from files (fnet-analyze) queries. It holds no ensembles.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/query/frame_lookup.hpp"

namespace fnet::query {

class LoadedFrames final : public FrameLookup {
 public:
  // Validates the frame (FrameError), computes its diagrams and keeps it as frame `index` of
  // `run`, replacing any frame held there. Its header names the run and the index only.
  void add(const std::string& run, std::uint32_t index, Frame network);

  std::shared_ptr<const AnalyzedFrame> frame(const std::string& run, std::uint32_t index) const override;
  std::shared_ptr<const AnalyzedFrame> row(const std::string& run, std::uint32_t index) const override {
    return frame(run, index);
  }
  std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> frames(const std::string& run) const override;
  Frame network(const std::string& run, std::uint32_t index) const override;
  std::vector<MemberRun> ensemble_members(const std::string& ensemble) const override;

 private:
  std::map<std::string, std::map<std::uint32_t, std::shared_ptr<const AnalyzedFrame>>> runs_;
};

}  // namespace fnet::query
