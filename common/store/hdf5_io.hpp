// Small typed helpers over the HDF5 C API: scalar attributes and 1-D/2-D arrays, every failure
// an h5::Error that names the object.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/store/hdf5_handle.hpp"

namespace fnet::h5 {

// Turns off HDF5's own error-stack printing: our exceptions carry the messages.
void quiet();

// File access with the latest format, which SWMR (single writer, readers while it writes) needs,
// and a chunk cache of kChunkCacheBytes per open dataset.
PropertyList latest_format();
// The chunk cache of each open dataset: two of the largest chunks a store or run file has (the
// points', 128 KiB), so that the chunk being appended to stays cached; chunks written in full are
// evicted first. HDF5's default (1 MiB a dataset) kept some 5 MB per store being written, full
// chunks that are never written again.
inline constexpr std::size_t kChunkCacheBytes = 256 << 10, kChunkCacheSlots = 101;
// How many times a SWMR reader reads a piece of metadata whose checksum fails before it gives up
// (HDF5's default is 100, with a growing sleep between attempts: half an hour on a file damaged
// on disk). A few attempts cover a read torn by a live writer.
inline constexpr unsigned kMetadataReadAttempts = 4;
// File access for a SWMR reader: the latest format and kMetadataReadAttempts.
PropertyList swmr_read_access();

// Opens a file read-only in SWMR mode with the latest format and kMetadataReadAttempts. Only a
// regular file is opened (after symbolic links): anything else (a FIFO, a device, a directory)
// is refused without being opened, since opening a FIFO blocks until a writer comes.
File open_for_reading(const std::string& path);

void write_attribute(hid_t obj, const char* name, double v);
void write_attribute(hid_t obj, const char* name, std::uint32_t v);
void write_attribute(hid_t obj, const char* name, std::uint64_t v);
void write_attribute(hid_t obj, const char* name, const std::string& v);  // variable-length UTF-8

double read_double(hid_t obj, const char* name, const std::string& where);
std::uint32_t read_uint32(hid_t obj, const char* name, const std::string& where);
std::uint64_t read_uint64(hid_t obj, const char* name, const std::string& where);
std::string read_string(hid_t obj, const char* name, const std::string& where);
// The reader for the type of `out`, for code generic in the attribute's type.
inline void read_attribute(hid_t obj, const char* name, const std::string& where, double& out) {
  out = read_double(obj, name, where);
}
inline void read_attribute(hid_t obj, const char* name, const std::string& where, std::uint32_t& out) {
  out = read_uint32(obj, name, where);
}
inline void read_attribute(hid_t obj, const char* name, const std::string& where, std::uint64_t& out) {
  out = read_uint64(obj, name, where);
}
inline void read_attribute(hid_t obj, const char* name, const std::string& where, std::string& out) {
  out = read_string(obj, name, where);
}

// rows x cols (cols == 0: a 1-D array of rows); zero rows are allowed.
void write_array(hid_t group, const char* name, const std::vector<double>& data, std::size_t rows, std::size_t cols);
void write_array(hid_t group, const char* name, const std::vector<std::uint32_t>& data, std::size_t rows,
                 std::size_t cols);
std::vector<double> read_doubles(hid_t group, const char* name, std::size_t cols, const std::string& where);
std::vector<std::uint32_t> read_uint32s(hid_t group, const char* name, std::size_t cols, const std::string& where);
std::vector<std::uint64_t> read_uint64s(hid_t group, const char* name, std::size_t cols, const std::string& where);
std::vector<std::int64_t> read_int64s(hid_t group, const char* name, std::size_t cols, const std::string& where);

// Extendible datasets (rows x cols, cols == 0 for 1-D), the only kind SWMR can grow.
void create_extendible(hid_t loc, const char* name, hid_t type, std::size_t cols, std::size_t chunk_rows);
// Appends `rows` rows (row-major) to an open extendible dataset.
void append_rows(hid_t dataset, hid_t type, const void* data, std::size_t rows, std::size_t cols);
// Reads rows [first, first + rows) of an open dataset (rows x cols, row-major) into `out`.
void read_rows(hid_t dataset, hid_t type, void* out, std::size_t first, std::size_t rows, std::size_t cols,
               const std::string& where);
// Throws unless `rows` rows of `row_bytes` bytes fit in the file that holds `dataset`: an
// uncompressed dataset (every one fnet writes) never holds more, and a corrupted extent must not
// make a reader allocate (or read) more than the file.
void check_fits_in_file(hid_t dataset, std::size_t rows, std::size_t row_bytes, const char* name,
                        const std::string& where);
// The number of rows of a dataset.
std::size_t row_count(hid_t loc, const char* name, const std::string& where);

// Names of the links in a group, in name order.
std::vector<std::string> member_names(hid_t group, const std::string& where);

}  // namespace fnet::h5
