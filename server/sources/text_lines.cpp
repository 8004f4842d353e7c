#include "server/sources/text_lines.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <sys/stat.h>

namespace fnet::sources {

void TextLines::Close::operator()(gzFile_s* file) const { gzclose(file); }

namespace {

// zlib's buffers (in, and twice that out) sized to what is left of the file, within [8 KiB,
// 128 KiB]: a large dump is read in large pieces, and a small file (a log, an index) costs no
// 384 KiB of buffers each time it is opened.
unsigned buffer_bytes(int fd, std::uint64_t offset) {
  constexpr std::uint64_t kMin = 8 << 10, kMax = 128 << 10;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_size < 0) return kMax;
  const std::uint64_t left =
      static_cast<std::uint64_t>(st.st_size) - std::min<std::uint64_t>(offset, static_cast<std::uint64_t>(st.st_size));
  return static_cast<unsigned>(std::clamp(left, kMin, kMax));
}

// zlib reads from the descriptor's position: the file opened and moved to `offset`, or null.
gzFile_s* open_at(const std::filesystem::path& path, std::uint64_t offset) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return nullptr;
  if (offset > 0 && ::lseek(fd, static_cast<off_t>(offset), SEEK_SET) != static_cast<off_t>(offset)) {
    ::close(fd);
    return nullptr;
  }
  gzFile_s* file = gzdopen(fd, "rb");
  if (!file) {
    ::close(fd);
    return nullptr;
  }
  gzbuffer(file, buffer_bytes(fd, offset));
  return file;
}

}  // namespace

TextLines::TextLines(const std::filesystem::path& path, const Start& start)
    : path_(path),
      file_(open_at(path, start.offset)),
      number_(start.line),
      offset_(start.offset),
      whole_lines_only_(start.whole_lines_only) {
  if (!file_) throw std::runtime_error(path.string() + ": cannot open");
}

bool TextLines::next(std::string& line) {
  line.clear();
  std::array<char, 4096> buffer;
  bool read_any = false;
  std::uint64_t bytes = 0;
  while (gzgets(file_.get(), buffer.data(), static_cast<int>(buffer.size())) != nullptr) {
    read_any = true;
    const std::size_t length = std::strlen(buffer.data());
    bytes += length;
    if (length > 0 && buffer[length - 1] == '\n') {
      line.append(buffer.data(), length - 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      ++number_;
      offset_ += bytes;
      return true;
    }
    line.append(buffer.data(), length);
  }
  int code = Z_OK;
  const char* message = gzerror(file_.get(), &code);
  if (code != Z_OK && code != Z_STREAM_END)
    throw std::runtime_error(path_.string() + ":" + std::to_string(number_ + 1) + ": " +
                             "compressed data cut short or corrupt (" + message + ")");
  if (!read_any || whole_lines_only_) {
    line.clear();
    return false;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  ++number_;
  offset_ += bytes;
  return true;
}

}  // namespace fnet::sources
