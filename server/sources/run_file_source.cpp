// The HDF5 run file fnet-simd --out writes (proto/run_file.md), both schemas.
#include <utility>

#include "common/store/run_file.hpp"
#include "server/sources/source_kinds.hpp"

namespace fnet::sources {

namespace {

// The committed frames are read when the file is opened, and handed out one by one.
class RunFile final : public FrameSource {
 public:
  explicit RunFile(const std::filesystem::path& path) : contents_(read_run_file(path)) {}
  const RunInfo& announcement() const override { return contents_.info; }
  std::optional<RunFrame> next() override {
    if (next_ == contents_.frames.size()) return std::nullopt;
    return std::move(contents_.frames[next_++]);
  }

 private:
  RunFileContents contents_;
  std::size_t next_ = 0;
};

std::unique_ptr<FrameSource> open_run_file(const SourceArguments& given) {
  return std::make_unique<RunFile>(given.at("run-file"));
}

}  // namespace

SourceKind run_file_kind() {
  return {"run file",
          {{"run-file", "F", "HDF5 run file written by fnet-simd --out", SourceFlag::Path::file}},
          true,
          open_run_file};
}

}  // namespace fnet::sources
