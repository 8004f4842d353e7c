// A file's whole content at once, as one view: the readers then parse in place, with no per-line or
// per-value allocation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

namespace fnet {

class FileText {
 public:
  // Empty when the file cannot be opened. Reads pipes and other non-regular files too.
  static std::optional<FileText> read(const std::filesystem::path& path);

  std::string_view view() const { return {data_.get(), size_}; }

 private:
  std::unique_ptr<char[]> data_;  // not zeroed first: the read fills it
  std::size_t size_ = 0;
};

}  // namespace fnet
