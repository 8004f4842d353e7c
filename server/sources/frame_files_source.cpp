// One frame's CSV files: the contacts, and optionally the particle table.
#include <utility>

#include "common/codec/frame_csv.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

class FrameFiles final : public FrameSource {
 public:
  FrameFiles(const std::filesystem::path& contacts, const std::optional<std::filesystem::path>& particles) {
    frame_.emplace();
    frame_->frame = read_frame_csv(contacts, particles);
    info_.frames = 1;
    info_.particles = static_cast<std::uint32_t>(frame_->frame.particle_count);
    info_.config_json = "{}";
  }
  const RunInfo& announcement() const override { return info_; }
  std::optional<RunFrame> next() override { return std::exchange(frame_, std::nullopt); }

 private:
  RunInfo info_;
  std::optional<RunFrame> frame_;  // until taken
};

std::unique_ptr<FrameSource> open_frame_files_kind(const SourceArguments& given) {
  const auto particles = given.find("particles");
  return open_frame_files(given.at("contacts"), particles == given.end()
                                                    ? std::nullopt
                                                    : std::optional<std::filesystem::path>(particles->second));
}

}  // namespace

std::unique_ptr<FrameSource> open_frame_files(const std::filesystem::path& contacts,
                                              const std::optional<std::filesystem::path>& particles) {
  return std::make_unique<FrameFiles>(contacts, particles);
}

SourceKind frame_files_kind() {
  return {"frame's CSV files",
          {{"contacts", "C.csv",
            "contacts CSV with header i,j,fn,ft: 0-based particle indices, signed normal force, tangential force "
            "(magnitudes are used); or i,j,fx,fy[,fz]: the force on grain i as a vector, split along the line of "
            "centres (needs --particles; proto/frames.md)",
            SourceFlag::Path::file},
           {"particles", "P.csv",
            "particles CSV with header id,x,y,r (id,x,y,r,z: a 3D frame); fixes the particle count so rattlers count "
            "(default: largest contact index + 1)",
            SourceFlag::Path::file, false}},
          false,
          open_frame_files_kind};
}

}  // namespace fnet::sources
