#include "common/codec/file_text.hpp"

#include <fstream>
#include <sstream>
#include <system_error>

namespace fnet {

std::optional<std::string> read_file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  std::string text(ec ? 0 : static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in && in.peek() == std::char_traits<char>::eof()) return text;
  in.clear();
  std::ostringstream rest;  // not a regular file (a pipe), or it grew while being read
  rest << in.rdbuf();
  return text + std::move(rest).str();
}

}  // namespace fnet
