#include "server/sources/source_kind.hpp"

#include <algorithm>
#include <set>

#include "server/sources/input_paths.hpp"

namespace fnet::sources {

namespace po = boost::program_options;

namespace {

bool takes(const SourceKind& kind, const std::string& flag) {
  return std::any_of(kind.flags.begin(), kind.flags.end(), [&](const SourceFlag& f) { return f.name == flag; });
}

// A switch is given when set; a flag with a value, when the value is not empty.
bool given(const po::variables_map& vm, const SourceFlag& flag) {
  if (!vm.count(flag.name)) return false;
  return flag.value_name.empty() ? vm[flag.name].as<bool>() : !vm[flag.name].as<std::string>().empty();
}

}  // namespace

std::string join_words(const std::vector<std::string>& words, const std::string& last) {
  std::string out;
  for (std::size_t k = 0; k < words.size(); ++k) {
    if (k > 0) out += k + 1 == words.size() ? " " + last + " " : ", ";
    out += words[k];
  }
  return out;
}

std::string kind_usage(const SourceKind& kind) {
  std::string out;
  for (const SourceFlag& flag : kind.flags) {
    std::string word = "--" + flag.name + (flag.value_name.empty() ? "" : " " + flag.value_name);
    if (!out.empty()) out += ' ';
    out += flag.required ? word : "[" + word + "]";
  }
  return out;
}

std::string source_usage(const std::vector<SourceKind>& kinds) {
  if (kinds.size() == 1) return kind_usage(kinds.front());
  std::string out;
  for (const SourceKind& kind : kinds) out += (out.empty() ? "(" : " | ") + kind_usage(kind);
  return out + ")";
}

void add_source_options(const std::vector<SourceKind>& kinds, po::options_description& options) {
  std::set<std::string> added;
  for (const SourceKind& kind : kinds)
    for (const SourceFlag& flag : kind.flags) {
      if (!added.insert(flag.name).second) continue;
      if (flag.value_name.empty()) {
        options.add_options()(flag.name.c_str(), po::bool_switch(), flag.meaning.c_str());
      } else {
        auto* value = po::value<std::string>();
        if (kinds.size() == 1 && &flag == &kind.flags.front() && flag.required) value->required();
        options.add_options()(flag.name.c_str(), value, flag.meaning.c_str());
      }
    }
}

ChosenSource choose_source(const std::vector<SourceKind>& kinds, const po::variables_map& vm) {
  std::vector<std::string> choosing;
  const SourceKind* chosen = nullptr;
  std::size_t count = 0;
  for (const SourceKind& kind : kinds) {
    choosing.push_back("--" + kind.flags.front().name);
    if (given(vm, kind.flags.front())) {
      chosen = &kind;
      ++count;
    }
  }
  if (count != 1) throw po::error("give exactly one of " + join_words(choosing, "and"));
  const std::string chooser = "--" + chosen->flags.front().name;
  for (const SourceKind& other : kinds)
    for (const SourceFlag& flag : other.flags)
      if (given(vm, flag) && !takes(*chosen, flag.name))
        throw po::error("--" + flag.name + " does not go with " + chooser);
  ChosenSource out{chosen, {}};
  for (const SourceFlag& flag : chosen->flags) {
    if (!given(vm, flag)) {
      if (flag.required) throw po::error(chooser + " needs --" + flag.name);
      continue;
    }
    const std::string value = flag.value_name.empty() ? "" : vm[flag.name].as<std::string>();
    if (flag.path == SourceFlag::Path::file) require_file("--" + flag.name, value);
    if (flag.path == SourceFlag::Path::directory) require_directory("--" + flag.name, value);
    out.given.emplace(flag.name, value);
  }
  return out;
}

}  // namespace fnet::sources
