// A file's whole content in one string, read at once: the readers then work on views into it,
// with no per-line or per-value allocation.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace fnet {

// Empty when the file cannot be opened. Reads pipes and other non-regular files too.
std::optional<std::string> read_file_text(const std::filesystem::path& path);

}  // namespace fnet
