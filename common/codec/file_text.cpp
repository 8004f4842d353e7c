#include "common/codec/file_text.hpp"

#include <cstring>
#include <fstream>
#include <system_error>

namespace fnet {

std::optional<FileText> FileText::read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::error_code ec;
  const std::uintmax_t expected = std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  FileText out;
  std::size_t capacity = ec ? 0 : static_cast<std::size_t>(expected);
  out.data_.reset(new char[capacity + 1]);
  // One read for a regular file; a pipe, or a file that grew meanwhile, reads on into a larger buffer.
  while (true) {
    in.read(out.data_.get() + out.size_, static_cast<std::streamsize>(capacity + 1 - out.size_));
    out.size_ += static_cast<std::size_t>(in.gcount());
    if (!in) break;
    capacity = 2 * capacity + 4096;
    std::unique_ptr<char[]> larger(new char[capacity + 1]);
    std::memcpy(larger.get(), out.data_.get(), out.size_);
    out.data_ = std::move(larger);
  }
  return out;
}

}  // namespace fnet
