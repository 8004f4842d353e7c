// The lines of a text file, gzip-compressed or not: zlib reads a file without the gzip magic as it
// is, so one reader serves both.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

struct gzFile_s;

namespace fnet::sources {

class TextLines {
 public:
  // Throws std::runtime_error "PATH: cannot open" when the file cannot be opened.
  explicit TextLines(const std::filesystem::path& path);

  // The next line without its '\n' (nor a '\r' before it); false at the end of the file. A
  // compressed stream that is cut short or corrupt throws "PATH:LINE: ..." naming the line it
  // stopped in.
  bool next(std::string& line);
  // The line last read, 1-based; 0 before the first.
  std::size_t number() const { return number_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Close {
    void operator()(gzFile_s* file) const;
  };
  std::filesystem::path path_;
  std::unique_ptr<gzFile_s, Close> file_;
  std::size_t number_ = 0;
};

}  // namespace fnet::sources
