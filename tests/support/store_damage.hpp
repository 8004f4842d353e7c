// Damage done to a real store file, as a disk, a careless edit or a hostile user would: bits
// flipped, one entry of a dataset overwritten, a global heap that HDF5 reads forever, the run
// given another id.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace fnet::testing {

// XORs one bit into every `stride`-th byte of [begin, end) of the file (end clipped to its size).
void flip_bits(const std::filesystem::path& file, std::size_t begin, std::size_t end, std::size_t stride);

// Sets entry (row, col) of dataset `name` (`cols` columns, 0 for a 1-D dataset) to `value`,
// converted to the dataset's integer type.
void set_entry(const std::filesystem::path& file, const char* name, std::size_t row, std::size_t col, std::size_t cols,
               std::uint64_t value);

// Damages the first global heap collection of the file (signature "GCOL"; variable-length strings
// live there, the store's attributes among them, and HDF5 does not checksum it): its first object
// gets index 0 and size 0, which HDF5 1.10's reader of the collection takes for free space of no
// length, read again forever. Throws when the file holds no collection.
void loop_global_heap(const std::filesystem::path& file);

// Gives the store another run id, in its run_id attribute and in every announcement it holds.
void rename_run(const std::filesystem::path& file, const std::string& run_id);

}  // namespace fnet::testing
