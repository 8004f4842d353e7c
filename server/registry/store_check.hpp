// A store the server did not write itself is read first by a child process under a deadline, and
// only then in the server. HDF5 1.10 may never return on a damaged file (a global heap, which it
// does not checksum, whose objects it reads again forever), and since HDF5 runs one call at a time
// under its own lock (a thread-safe build), a read that never returns would stall every store of
// the server. The child reads the store whole, as the server will (read_whole_store_in_data_dir);
// one past the deadline is killed. A child checks several stores in turn (starting one costs
// about as much as reading a store of 100 frames), each with the whole deadline.
//
// The check's command gets the stores' paths after its own arguments and answers each in turn on a
// line of its stdout: kStorePassed, or why the store is refused. A child that ends or is killed
// before it answers refuses the store it was at (with its exit status), and the stores after it
// are checked by another.
inline constexpr const char* kStorePassed = "ok";
#pragma once

#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace fnet::server {

struct StoreCheckOptions {
  std::vector<std::string> command;  // the checker and its first arguments; the stores' paths follow
  double seconds = 30;               // a check still running after this is killed, its store refused
  unsigned parallel = 2;             // children checking at once
};

class StoreChecker {
 public:
  explicit StoreChecker(StoreCheckOptions options) : options_(std::move(options)) {}

  // For each file, in order: empty when this process may read it, else why it is refused, naming
  // the file. Anything but a regular file is not checked (read_store refuses it unopened). A file
  // whose device, inode, size and modification time are those of its last check is not checked
  // again; one that changed while it was checked is refused until it is checked unchanged.
  // Thread-safe; returns within about options.seconds for every `parallel` files checked.
  std::vector<std::string> refusals(const std::vector<std::filesystem::path>& files);

 private:
  struct Identity {
    dev_t device = 0;
    ino_t inode = 0;
    off_t size = 0;
    timespec modified{};
    bool operator==(const Identity& o) const;
  };
  struct Verdict {
    Identity identity;
    std::string refusal;  // empty: passed
  };
  // The identity of a regular file (after symbolic links); nullopt for anything else.
  static std::optional<Identity> identity(const std::filesystem::path& file);
  // The checks of `files[k]` for each k of `which`, into out[k].
  void check(const std::vector<std::filesystem::path>& files, const std::vector<std::size_t>& which,
             std::vector<std::string>& out) const;

  const StoreCheckOptions options_;
  std::mutex mutex_;                                   // guards verdicts_
  std::map<std::filesystem::path, Verdict> verdicts_;  // one per store file name checked
};

}  // namespace fnet::server
