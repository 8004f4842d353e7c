#include "server/sources/text_lines.hpp"

#include <zlib.h>

#include <array>
#include <cstring>
#include <stdexcept>

namespace fnet::sources {

void TextLines::Close::operator()(gzFile_s* file) const { gzclose(file); }

TextLines::TextLines(const std::filesystem::path& path) : path_(path), file_(gzopen(path.c_str(), "rb")) {
  if (!file_) throw std::runtime_error(path.string() + ": cannot open");
  gzbuffer(file_.get(), 1 << 17);
}

bool TextLines::next(std::string& line) {
  line.clear();
  std::array<char, 4096> buffer;
  bool read_any = false;
  while (gzgets(file_.get(), buffer.data(), static_cast<int>(buffer.size())) != nullptr) {
    read_any = true;
    const std::size_t length = std::strlen(buffer.data());
    if (length > 0 && buffer[length - 1] == '\n') {
      line.append(buffer.data(), length - 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      ++number_;
      return true;
    }
    line.append(buffer.data(), length);
  }
  int code = Z_OK;
  const char* message = gzerror(file_.get(), &code);
  if (code != Z_OK && code != Z_STREAM_END)
    throw std::runtime_error(path_.string() + ":" + std::to_string(number_ + 1) + ": " +
                             "compressed data cut short or corrupt (" + message + ")");
  if (!read_any) return false;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  ++number_;
  return true;
}

}  // namespace fnet::sources
