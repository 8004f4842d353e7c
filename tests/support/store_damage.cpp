#include "tests/support/store_damage.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/store/hdf5_io.hpp"

namespace fnet::testing {

namespace fs = std::filesystem;

void flip_bits(const fs::path& file, std::size_t begin, std::size_t end, std::size_t stride) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  end = std::min<std::size_t>(end, fs::file_size(file));
  for (std::size_t at = begin; at < end; at += stride) {
    f.seekg(static_cast<std::streamoff>(at));
    char c = 0;
    f.get(c);
    f.seekp(static_cast<std::streamoff>(at));
    f.put(static_cast<char>(c ^ 0x10));
  }
}

namespace {

h5::File open_for_writing(const fs::path& file) {
  const h5::PropertyList fapl = h5::latest_format();
  return h5::File(H5Fopen(file.c_str(), H5F_ACC_RDWR, fapl.get()), "open " + file.string());
}

}  // namespace

void set_entry(const fs::path& file, const char* name, std::size_t row, std::size_t col, std::size_t cols,
               std::uint64_t value) {
  const h5::File f = open_for_writing(file);
  h5::Dataset set(H5Dopen2(f.get(), name, H5P_DEFAULT), std::string("open ") + name);
  h5::Dataspace space(H5Dget_space(set.get()), "space");
  const hsize_t start[2] = {row, col}, count[2] = {1, 1};
  h5::check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), "select");
  h5::Dataspace one(H5Screate_simple(cols ? 2 : 1, count, nullptr), "one");
  h5::check(H5Dwrite(set.get(), H5T_NATIVE_UINT64, one.get(), space.get(), H5P_DEFAULT, &value), "write");
}

void loop_global_heap(const fs::path& file) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::size_t heap = bytes.find("GCOL");
  if (heap == std::string::npos) throw std::runtime_error(file.string() + ": no global heap collection");
  // The collection's header: signature, version, 3 reserved bytes, its size (8 bytes). Each object:
  // index (2 bytes), reference count (2), 4 reserved, size (8), data.
  constexpr std::size_t kHeader = 16, kSizeAt = 8;
  const char zeros[8] = {};
  f.seekp(static_cast<std::streamoff>(heap + kHeader));
  f.write(zeros, 2);
  f.seekp(static_cast<std::streamoff>(heap + kHeader + kSizeAt));
  f.write(zeros, 8);
}

void rename_run(const fs::path& file, const std::string& run_id) {
  const h5::File f = open_for_writing(file);
  h5::Group root(H5Gopen2(f.get(), "/", H5P_DEFAULT), "open /");
  h5::check(H5Adelete(root.get(), "run_id"), "delete run_id");
  h5::write_attribute(root.get(), "run_id", run_id);
  h5::Dataset set(H5Dopen2(f.get(), "announcements", H5P_DEFAULT), "open announcements");
  h5::Datatype type(H5Dget_type(set.get()), "type");
  const std::size_t bytes = H5Tget_size(type.get());
  const std::size_t rows = h5::row_count(f.get(), "announcements", "announcements");
  std::vector<char> raw(rows * bytes);
  if (rows == 0) return;
  h5::check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), "read announcements");
  for (std::size_t k = 0; k < rows; ++k) {
    char* row = raw.data() + k * bytes;
    nlohmann::json info = nlohmann::json::parse(std::string(row, strnlen(row, bytes)));
    info["run"] = run_id;
    const std::string text = info.dump();
    std::fill_n(row, bytes, '\0');
    std::copy_n(text.begin(), std::min(text.size(), bytes), row);
  }
  h5::check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), "write announcements");
}

}  // namespace fnet::testing
