#include "server/fnet-server/token_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>

#include "server/rpc/access.hpp"

namespace fnet::server {

namespace {

// Closes the descriptor it holds.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

std::runtime_error failure(const std::string& path, const std::string& what) {
  return std::runtime_error("token file '" + path + "': " + what + ": " + std::strerror(errno));
}

// 32 bytes of the kernel's CSPRNG in base64url without padding: 43 characters.
std::string random_token(const std::string& path) {
  std::array<unsigned char, 32> bytes{};
  std::ifstream random("/dev/urandom", std::ios::binary);
  if (!random.read(reinterpret_cast<char*>(bytes.data()), bytes.size()))
    throw std::runtime_error("token file '" + path + "': cannot read /dev/urandom");
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::string token;
  unsigned bits = 0, held = 0;
  for (unsigned char b : bytes) {
    bits = (bits << 8) | b;
    held += 8;
    while (held >= 6) token += kAlphabet[(bits >> (held -= 6)) & 63];
  }
  if (held > 0) token += kAlphabet[(bits << (6 - held)) & 63];
  return token;
}

}  // namespace

std::string ensure_token_file(const std::string& path) {
  const FileDescriptor fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600));
  if (fd.get() < 0) {
    if (errno != EEXIST) throw failure(path, "cannot create it");
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw failure(path, "cannot read its mode");
    if (st.st_mode & (S_IRWXG | S_IRWXO)) {
      std::ostringstream mode;
      mode << std::oct << (st.st_mode & 0777);
      throw std::runtime_error("token file '" + path + "': others than its owner may use it (mode 0" + mode.str() +
                               "); make it mode 0600 or remove it");
    }
    return rpc::read_token_file(path);
  }
  if (::fchmod(fd.get(), 0600) != 0) throw failure(path, "cannot make it mode 0600");
  const std::string token = random_token(path);
  const std::string line = token + "\n";
  if (::write(fd.get(), line.data(), line.size()) != static_cast<ssize_t>(line.size()))
    throw failure(path, "cannot write it");
  if (::fsync(fd.get()) != 0) throw failure(path, "cannot write it");
  return token;
}

}  // namespace fnet::server
