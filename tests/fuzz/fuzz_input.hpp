// What the fuzz targets share: an input cut into the files a reader takes, a scratch folder of the
// process's own to write them in, typed values taken from the bytes, and the rule every error
// message obeys (it names the input at fault).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fnet::fuzz {

// What separates the files of one input: "a\n@@@@\nb" is the files "a" and "b" (a file that ends
// with a newline is followed by one more), so that a file may end anywhere, even inside a line.
inline constexpr std::string_view kFileSeparator = "\n@@@@\n";

// The input's files, in order; at least one (perhaps empty).
std::vector<std::string_view> input_files(const std::uint8_t* data, std::size_t size);

// A folder of this process's own under $TMPDIR (else /dev/shm, else /tmp), removed at exit: the
// readers under test take paths.
const std::filesystem::path& scratch_dir();
// Writes `bytes` to scratch_dir()/name and returns that path.
std::filesystem::path write_file(const std::string& name, std::string_view bytes);
// Removes every file of scratch_dir(), so that no input sees another's files.
void clear_scratch();

// Values taken from the front of the bytes: zero once they run out.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}

  template <class T>
  T take() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value{};
    const std::size_t n = std::min(sizeof value, left());
    std::memcpy(&value, p_, n);
    p_ += n;
    return value;
  }
  // An integer in [0, bound]: most inputs want small counts.
  std::size_t take_count(std::size_t bound) { return bound == 0 ? 0 : take<std::uint16_t>() % (bound + 1); }
  std::string take_string(std::size_t max_bytes);
  std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

// Aborts, printing the message, unless it names one of `inputs` (a path, a label): an error a
// user cannot place is a finding, as a crash is. With FNET_FUZZ_VERBOSE set, prints every message.
void require_names(const std::exception& e, std::initializer_list<std::string_view> inputs);

}  // namespace fnet::fuzz
