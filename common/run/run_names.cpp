#include "common/run/run_names.hpp"

#include <cctype>

namespace fnet {

std::string name_problem(const std::string& name, const std::string& what) {
  if (name.empty()) return what + " is empty";
  if (name.size() > 64) return what + " longer than 64 characters";
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-'))
      return what + " '" + name + "' has a character outside [A-Za-z0-9._-]";
  if (name == "." || name == "..") return what + " '" + name + "' is not a name";
  return {};
}

std::string run_id_problem(const std::string& run_id) { return name_problem(run_id, "run id"); }

}  // namespace fnet
