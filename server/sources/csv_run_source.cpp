// A run folder as fnet-simd --export-csv writes it: index.csv, then each frame's CSV files.
#include <utility>

#include "common/codec/run_csv.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

// Reads index.csv and the first frame when opened (the announcement counts its particles), every
// later frame when it is asked for.
class CsvRun final : public FrameSource {
 public:
  explicit CsvRun(std::filesystem::path dir) : dir_(std::move(dir)), index_(read_csv_index(dir_, "")) {
    info_.frames = static_cast<std::uint32_t>(index_.size());
    info_.config_json = "{}";
    if (!index_.empty()) {
      first_ = read_csv_frame(dir_, index_.front());
      info_.particles = static_cast<std::uint32_t>(first_->frame.particle_count);
    }
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override {
    if (next_ == index_.size()) return std::nullopt;
    const std::size_t k = next_++;
    return k == 0 ? std::exchange(first_, std::nullopt) : read_csv_frame(dir_, index_[k]);
  }

 private:
  std::filesystem::path dir_;
  std::vector<FrameHeader> index_;
  RunInfo info_;
  std::optional<RunFrame> first_;
  std::size_t next_ = 0;
};

std::unique_ptr<FrameSource> open_csv_run(const SourceArguments& given) {
  return std::make_unique<CsvRun>(given.at("csv-dir"));
}

}  // namespace

SourceKind csv_run_kind() {
  return {"CSV folder",
          {{"csv-dir", "DIR",
            "a run folder: index.csv (frame[,step][,time],rho,z; an experiment without steps may leave step out) + "
            "frame_NNNN_contacts.csv [+ frame_NNNN_particles.csv], as fnet-simd --export-csv writes it",
            SourceFlag::Path::directory}},
          false,
          open_csv_run};
}

}  // namespace fnet::sources
