#include "common/store/hdf5_io.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <string_view>
#include <sys/stat.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FNET_HDF5_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(FNET_HDF5_UNDER_ASAN)
// HDF5 1.10 loses an object header (H5O_t, from its free list) when a header fails its checksum:
// a leak inside the library on its own error path, which LeakSanitizer reports at exit. Every hid_t
// still open at exit is released by HDF5's own atexit handler, so no leak of ours can show up in
// libhdf5 frames: suppressing them hides nothing this code could cause.
extern "C" const char* __lsan_default_suppressions() { return "leak:libhdf5\n"; }
#endif

namespace fnet::h5 {
namespace {

void write_scalar(hid_t obj, const char* name, hid_t type, const void* value) {
  Dataspace space(H5Screate(H5S_SCALAR), "H5Screate");
  Attribute attr(H5Acreate2(obj, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 std::string("create attribute ") + name);
  check(H5Awrite(attr.get(), type, value), std::string("write attribute ") + name);
}

template <class T>
T read_scalar(hid_t obj, const char* name, hid_t type, const std::string& where) {
  if (H5Aexists(obj, name) <= 0) throw Error(where + ": attribute '" + name + "' missing");
  Attribute attr(H5Aopen(obj, name, H5P_DEFAULT), where + ": open attribute " + name);
  T value{};
  check(H5Aread(attr.get(), type, &value), where + ": read attribute " + name);
  return value;
}

void write_any_array(hid_t group, const char* name, hid_t type, const void* data, std::size_t rows, std::size_t cols) {
  const std::array<hsize_t, 2> dims{rows, cols};
  Dataspace space(H5Screate_simple(cols ? 2 : 1, dims.data(), nullptr), "H5Screate_simple");
  Dataset set(H5Dcreate2(group, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              std::string("create dataset ") + name);
  if (rows > 0) check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), std::string("write ") + name);
}

template <class T>
std::vector<T> read_any_array(hid_t group, const char* name, hid_t type, std::size_t cols, const std::string& where) {
  if (H5Lexists(group, name, H5P_DEFAULT) <= 0) throw Error(where + ": dataset '" + name + "' missing");
  Dataset set(H5Dopen2(group, name, H5P_DEFAULT), where + ": open " + name);
  Dataspace space(H5Dget_space(set.get()), where + ": space of " + name);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (rank != (cols ? 2 : 1) || (cols && dims[1] != cols))
    throw Error(where + ": dataset '" + name + "' has the wrong shape");
  check_fits_in_file(set.get(), dims[0], (cols ? cols : 1) * sizeof(T), name, where);
  std::vector<T> out(dims[0] * (cols ? cols : 1));
  if (!out.empty())
    check(H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), where + ": read " + name);
  return out;
}

}  // namespace

std::string system_cause() {
  std::string cause;
  // The innermost error naming a system error wins: it is the one the others report.
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
        static constexpr std::string_view kMark = "error message = '";
        const std::string_view desc = e->desc ? e->desc : "";
        if (const auto at = desc.find(kMark); at != std::string_view::npos) {
          const auto begin = at + kMark.size(), end = desc.find('\'', begin);
          if (end != std::string_view::npos) *static_cast<std::string*>(out) = desc.substr(begin, end - begin);
        }
        return 0;
      },
      &cause);
  return cause.empty() ? cause : " (" + cause + ")";
}

void check_fits_in_file(hid_t dataset, std::size_t rows, std::size_t row_bytes, const char* name,
                        const std::string& where) {
  Handle<H5Fclose> file(H5Iget_file_id(dataset), where + ": file of " + name);
  hsize_t file_bytes = 0;
  check(H5Fget_filesize(file.get(), &file_bytes), where + ": size of the file");
  if (row_bytes != 0 && rows > file_bytes / row_bytes)
    throw Error(where + ": dataset '" + name + "' claims " + std::to_string(rows) + " rows of " +
                std::to_string(row_bytes) + " bytes, more than the file's " + std::to_string(file_bytes) + " bytes");
}

File open_for_reading(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw Error(path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw Error(path + ": not a regular file");
  const PropertyList fapl = swmr_read_access();
  return File(H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl.get()),
              "open " + path + " (not an HDF5 store?)");
}

PropertyList latest_format() {
  PropertyList fapl(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
  check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "H5Pset_libver_bounds");
  check(H5Pset_cache(fapl.get(), 0, kChunkCacheSlots, kChunkCacheBytes, 1.0), "H5Pset_cache");
  return fapl;
}

PropertyList swmr_read_access() {
  PropertyList fapl = latest_format();
  check(H5Pset_metadata_read_attempts(fapl.get(), kMetadataReadAttempts), "H5Pset_metadata_read_attempts");
  return fapl;
}

void quiet() {
  // HDF5's error printing is set per thread: every thread that opens a store silences its own.
  thread_local const bool once = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)once;
}

void write_attribute(hid_t obj, const char* name, double v) { write_scalar(obj, name, H5T_NATIVE_DOUBLE, &v); }
void write_attribute(hid_t obj, const char* name, std::uint32_t v) { write_scalar(obj, name, H5T_NATIVE_UINT32, &v); }
void write_attribute(hid_t obj, const char* name, std::uint64_t v) { write_scalar(obj, name, H5T_NATIVE_UINT64, &v); }

// Variable-length UTF-8, which h5py reads as str (fixed-length strings come back as bytes).
void write_attribute(hid_t obj, const char* name, const std::string& v) {
  Datatype type(H5Tcopy(H5T_C_S1), "H5Tcopy");
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  const char* text = v.c_str();
  write_scalar(obj, name, type.get(), &text);
}

double read_double(hid_t obj, const char* name, const std::string& where) {
  return read_scalar<double>(obj, name, H5T_NATIVE_DOUBLE, where);
}
std::uint32_t read_uint32(hid_t obj, const char* name, const std::string& where) {
  return read_scalar<std::uint32_t>(obj, name, H5T_NATIVE_UINT32, where);
}
std::uint64_t read_uint64(hid_t obj, const char* name, const std::string& where) {
  return read_scalar<std::uint64_t>(obj, name, H5T_NATIVE_UINT64, where);
}

std::string read_string(hid_t obj, const char* name, const std::string& where) {
  if (H5Aexists(obj, name) <= 0) throw Error(where + ": attribute '" + name + "' missing");
  Attribute attr(H5Aopen(obj, name, H5P_DEFAULT), where + ": open attribute " + name);
  Datatype type(H5Aget_type(attr.get()), where + ": attribute type " + name);
  if (H5Tis_variable_str(type.get()) > 0) {
    char* text = nullptr;
    Datatype mem(H5Tget_native_type(type.get(), H5T_DIR_ASCEND), "native type");
    check(H5Aread(attr.get(), mem.get(), &text), where + ": read attribute " + name);
    std::string out = text ? text : "";
    H5free_memory(text);
    return out;
  }
  std::string out(H5Tget_size(type.get()), '\0');
  check(H5Aread(attr.get(), type.get(), out.data()), where + ": read attribute " + name);
  out.resize(out.find('\0') == std::string::npos ? out.size() : out.find('\0'));
  return out;
}

void write_array(hid_t group, const char* name, const std::vector<double>& data, std::size_t rows, std::size_t cols) {
  write_any_array(group, name, H5T_NATIVE_DOUBLE, data.data(), rows, cols);
}
void write_array(hid_t group, const char* name, const std::vector<std::uint32_t>& data, std::size_t rows,
                 std::size_t cols) {
  write_any_array(group, name, H5T_NATIVE_UINT32, data.data(), rows, cols);
}
std::vector<double> read_doubles(hid_t group, const char* name, std::size_t cols, const std::string& where) {
  return read_any_array<double>(group, name, H5T_NATIVE_DOUBLE, cols, where);
}
std::vector<std::uint32_t> read_uint32s(hid_t group, const char* name, std::size_t cols, const std::string& where) {
  return read_any_array<std::uint32_t>(group, name, H5T_NATIVE_UINT32, cols, where);
}

void create_extendible(hid_t loc, const char* name, hid_t type, std::size_t cols, std::size_t chunk_rows) {
  const int rank = cols ? 2 : 1;
  const std::array<hsize_t, 2> dims{0, cols}, max{H5S_UNLIMITED, cols}, chunk{chunk_rows, cols ? cols : 1};
  Dataspace space(H5Screate_simple(rank, dims.data(), max.data()), "H5Screate_simple");
  PropertyList props(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate");
  check(H5Pset_chunk(props.get(), rank, chunk.data()), std::string("chunk ") + name);
  Dataset set(H5Dcreate2(loc, name, type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
              std::string("create dataset ") + name);
}

void append_rows(hid_t dataset, hid_t type, const void* data, std::size_t rows, std::size_t cols) {
  if (rows == 0) return;
  Dataspace current(H5Dget_space(dataset), "H5Dget_space");
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(current.get(), dims.data(), nullptr);
  const int rank = cols ? 2 : 1;
  const std::array<hsize_t, 2> grown{dims[0] + rows, cols}, start{dims[0], 0}, count{rows, cols};
  check(H5Dset_extent(dataset, grown.data()), "H5Dset_extent");
  Dataspace file_space(H5Dget_space(dataset), "H5Dget_space");
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select rows");
  Dataspace memory(H5Screate_simple(rank, count.data(), nullptr), "H5Screate_simple");
  check(H5Dwrite(dataset, type, memory.get(), file_space.get(), H5P_DEFAULT, data), "append rows");
}

void read_rows(hid_t dataset, hid_t type, void* out, std::size_t first, std::size_t rows, std::size_t cols,
               const std::string& where) {
  if (rows == 0) return;
  Dataspace file_space(H5Dget_space(dataset), where + ": H5Dget_space");
  const int rank = cols ? 2 : 1;
  const std::array<hsize_t, 2> start{first, 0}, count{rows, cols};
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        where + ": select rows");
  Dataspace memory(H5Screate_simple(rank, count.data(), nullptr), where + ": H5Screate_simple");
  check(H5Dread(dataset, type, memory.get(), file_space.get(), H5P_DEFAULT, out), where + ": read rows");
}

std::vector<std::uint64_t> read_uint64s(hid_t loc, const char* name, std::size_t cols, const std::string& where) {
  return read_any_array<std::uint64_t>(loc, name, H5T_NATIVE_UINT64, cols, where);
}
std::vector<std::int64_t> read_int64s(hid_t loc, const char* name, std::size_t cols, const std::string& where) {
  return read_any_array<std::int64_t>(loc, name, H5T_NATIVE_INT64, cols, where);
}

std::size_t row_count(hid_t loc, const char* name, const std::string& where) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) throw Error(where + ": dataset '" + name + "' missing");
  Dataset set(H5Dopen2(loc, name, H5P_DEFAULT), where + ": open " + name);
  Dataspace space(H5Dget_space(set.get()), where + ": space of " + name);
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims[0];
}

std::vector<std::string> member_names(hid_t group, const std::string& where) {
  H5G_info_t info{};
  check(H5Gget_info(group, &info), where + ": list members");
  std::vector<std::string> out;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t size = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (size < 0) throw Error(where + ": name of member " + std::to_string(k));
    std::string name(static_cast<std::size_t>(size) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(), H5P_DEFAULT);
    name.pop_back();
    out.push_back(std::move(name));
  }
  return out;
}

}  // namespace fnet::h5
