// The lines of a text file, gzip-compressed or not: zlib reads a file without the gzip magic as it
// is, so one reader serves both.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

struct gzFile_s;

namespace fnet::sources {

class TextLines {
 public:
  // Where to start, and whether a last line without its newline is a line. A file still being
  // written is read from a byte `offset` of an uncompressed file (line numbers counted from
  // `line`, the number of the line before it), whole lines only: a line not yet ended is not read.
  struct Start {
    std::uint64_t offset = 0;
    std::size_t line = 0;
    bool whole_lines_only = false;
  };

  // Throws std::runtime_error "PATH: cannot open" when the file cannot be opened.
  explicit TextLines(const std::filesystem::path& path) : TextLines(path, Start{}) {}
  TextLines(const std::filesystem::path& path, const Start& start);

  // The next line without its '\n' (nor a '\r' before it); false at the end of the file. A
  // compressed stream that is cut short or corrupt throws "PATH:LINE: ..." naming the line it
  // stopped in.
  bool next(std::string& line);
  // The line last read, 1-based; 0 before the first.
  std::size_t number() const { return number_; }
  const std::filesystem::path& path() const { return path_; }
  // The byte after the line last read, in the uncompressed text.
  std::uint64_t offset() const { return offset_; }

 private:
  struct Close {
    void operator()(gzFile_s* file) const;
  };
  std::filesystem::path path_;
  std::unique_ptr<gzFile_s, Close> file_;
  std::size_t number_ = 0;
  std::uint64_t offset_ = 0;
  bool whole_lines_only_ = false;
};

}  // namespace fnet::sources
