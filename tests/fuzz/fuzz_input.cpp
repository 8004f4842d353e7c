#include "tests/fuzz/fuzz_input.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <system_error>

namespace fnet::fuzz {
namespace {

// Where scratch folders go: $TMPDIR, else /dev/shm (tmpfs: an input's files never reach a disk,
// where ext4 flushes a file rewritten after a truncation when it is closed), else /tmp.
std::string scratch_root() {
  const char* tmp = std::getenv("TMPDIR");
  if (tmp && *tmp) return tmp;
  std::error_code ec;
  if (std::filesystem::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0) return "/dev/shm";
  return "/tmp";
}

// Made at first use, removed when the process exits normally (a crash leaves it for the report).
struct ScratchFolder {
  std::filesystem::path path;
  ScratchFolder() {
    std::string pattern = scratch_root() + "/fnet-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      std::cerr << "fuzz: cannot create a scratch folder " << pattern << "\n";
      std::abort();
    }
    path = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

std::vector<std::string_view> input_files(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> out;
  for (std::size_t at; (at = text.find(kFileSeparator)) != std::string_view::npos;) {
    out.push_back(text.substr(0, at));
    text.remove_prefix(at + kFileSeparator.size());
  }
  out.push_back(text);
  return out;
}

const std::filesystem::path& scratch_dir() {
  static const ScratchFolder folder;
  return folder.path;
}

std::filesystem::path write_file(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) {
    std::cerr << "fuzz: cannot write " << path << "\n";
    std::abort();
  }
  return path;
}

void clear_scratch() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(scratch_dir(), ec))
    std::filesystem::remove_all(entry.path(), ec);
}

std::string ByteReader::take_string(std::size_t max_bytes) {
  const std::size_t n = std::min(take_count(max_bytes), left());
  std::string out(reinterpret_cast<const char*>(p_), n);
  p_ += n;
  return out;
}

void require_names(const std::exception& e, std::initializer_list<std::string_view> inputs) {
  const std::string_view message = e.what();
  static const bool verbose = std::getenv("FNET_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::cerr << "fuzz: refused: " << message << "\n";
  if (std::any_of(inputs.begin(), inputs.end(),
                  [&](std::string_view input) { return message.find(input) != std::string_view::npos; }))
    return;
  std::cerr << "fuzz: an error that names none of the inputs: " << message << "\n";
  std::abort();
}

}  // namespace fnet::fuzz
