#include "server/query/loaded_frames.hpp"

#include "common/analysis/frame_analysis.hpp"
#include "server/query/query_errors.hpp"

namespace fnet::query {

void LoadedFrames::add(const std::string& run, std::uint32_t index, Frame network) {
  validate(network);
  auto f = std::make_shared<AnalyzedFrame>();
  f->header.run_id = run;
  f->header.index = index;
  f->diagrams = analyze_frame(network);
  f->network = std::make_shared<const Frame>(std::move(network));
  runs_[run][index] = std::move(f);
}

std::shared_ptr<const AnalyzedFrame> LoadedFrames::frame(const std::string& run, std::uint32_t index) const {
  const auto r = runs_.find(run);
  if (r == runs_.end()) return nullptr;
  const auto f = r->second.find(index);
  return f == r->second.end() ? nullptr : f->second;
}

std::optional<std::vector<std::shared_ptr<const AnalyzedFrame>>> LoadedFrames::frames(const std::string& run) const {
  const auto r = runs_.find(run);
  if (r == runs_.end()) return std::nullopt;
  std::vector<std::shared_ptr<const AnalyzedFrame>> out;
  for (const auto& [index, f] : r->second) out.push_back(f);
  return out;
}

Frame LoadedFrames::network(const std::string& run, std::uint32_t index) const {
  const auto f = frame(run, index);
  if (!f) throw NoNetwork(run, index, "run '" + run + "' holds no frame " + std::to_string(index));
  return *f->network;
}

std::vector<MemberRun> LoadedFrames::ensemble_members(const std::string&) const { return {}; }

}  // namespace fnet::query
