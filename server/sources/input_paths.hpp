// The checks that an input named on the command line is there, made before any work.
#pragma once

#include <filesystem>
#include <string>

namespace fnet::sources {

// Usage errors, before any work: "<what> <path>: no such file" (or directory).
void require_file(const std::string& what, const std::filesystem::path& path);
void require_directory(const std::string& what, const std::filesystem::path& path);

}  // namespace fnet::sources
