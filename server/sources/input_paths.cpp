#include "server/sources/input_paths.hpp"

#include <boost/program_options.hpp>

namespace fnet::sources {

void require_file(const std::string& what, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw boost::program_options::error(what + " " + path.string() + ": no such file");
  if (fs::is_directory(path))
    throw boost::program_options::error(what + " " + path.string() + ": is a directory, not a file");
}

void require_directory(const std::string& what, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw boost::program_options::error(what + " " + path.string() + ": no such directory");
  if (!fs::is_directory(path)) throw boost::program_options::error(what + " " + path.string() + ": not a directory");
}

}  // namespace fnet::sources
