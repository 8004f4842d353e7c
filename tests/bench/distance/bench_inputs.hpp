// What the in-process distance benchmarks share: their command line ([--repeat R] then pairs of
// diagram files) and reading one dimension of an `fnet-analyze diagram` document.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/codec/diagram_json.hpp"

namespace fnet::bench {

struct PairArgs {
  int repeat;
  std::vector<std::string> files;  // A.json B.json, pair after pair
};

// Exits with the usage line when the files do not come in pairs.
inline PairArgs parse_pair_args(int argc, char** argv, const char* name, int repeat) {
  PairArgs out{repeat, {}};
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--repeat" && k + 1 < argc) {
      out.repeat = std::max(1, std::atoi(argv[++k]));
    } else {
      out.files.push_back(arg);
    }
  }
  if (out.files.empty() || out.files.size() % 2) {
    std::fprintf(stderr, "usage: %s [--repeat R] A.json B.json [...]\n", name);
    std::exit(2);
  }
  return out;
}

inline Diagram load_diagram(const std::string& path, int dim) {
  std::ifstream in(path);
  return diagram_from_json(nlohmann::json::parse(in).at(dim ? "pd1" : "pd0"));
}

// "A.json->B.json" from the pair's paths.
inline std::string pair_name(const std::string& a, const std::string& b) {
  return a.substr(a.rfind('/') + 1) + "->" + b.substr(b.rfind('/') + 1);
}

}  // namespace fnet::bench
