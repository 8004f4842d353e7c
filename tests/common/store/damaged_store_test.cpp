// A store damaged on disk is refused promptly, naming the file and what is wrong: a piece of
// metadata that fails its checksum is read h5::kMetadataReadAttempts times, not HDF5's default of a
// hundred times with longer and longer sleeps, meant for a writer caught mid-flush, which held a
// server's start for over ten minutes; offsets that decrease, which had the reader index past its
// arrays or ask for exabytes, are named.
#include <chrono>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_io.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

// Flips every bit of the byte at `offset` of the file.
void flip_store_byte(const fs::path& path, std::uint64_t offset) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  const char byte = static_cast<char>(~file.get());
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(byte);
}

// A store of two frames, each with its diagrams and a network of three grains and two contacts.
void write_damageable_store(const fs::path& path) {
  StoreWriter w(path, "damaged");
  for (std::uint32_t index = 0; index < 2; ++index) {
    AnalyzedFrame f;
    f.header = {"damaged", index, index, 0.0, 0.7, 3.5};
    f.diagrams.normal.pd0 = {{3.0, 1.0}, {2.0, -1.0}};
    f.diagrams.normal.pd1 = {{2.0, 1.0}};
    f.diagrams.normal.vertices = 3;
    auto network = std::make_shared<Frame>();
    network->particle_count = 3;
    network->particles = {{0, 0, 0.5}, {1, 0, 0.5}, {2, 0, 0.5}};
    network->contacts = {{0, 1, 1.0, 0.5}, {1, 2, 2.0, 0.5}};
    f.network = network;
    w.append(f);
  }
}

// Overwrites row `row` of a 2-D dataset of unsigned 64-bit integers.
void overwrite_store_row(const fs::path& path, const char* name, hsize_t row,
                         const std::vector<std::uint64_t>& values) {
  h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open");
  h5::Dataset set(H5Dopen2(file.get(), name, H5P_DEFAULT), name);
  h5::Dataspace space(H5Dget_space(set.get()), "space");
  const hsize_t start[2] = {row, 0}, count[2] = {1, values.size()};
  h5::check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), "select");
  h5::Dataspace memory(H5Screate_simple(2, count, nullptr), "memory");
  h5::check(H5Dwrite(set.get(), H5T_NATIVE_UINT64, memory.get(), space.get(), H5P_DEFAULT, values.data()), "write");
}

std::string store_refusal(const fs::path& path) {
  try {
    const StoredRun run = read_store(path);
    for (const AnalyzedFrame& f : run.frames) read_network(path, f.header.index);
  } catch (const h5::Error& e) {
    return e.what();
  }
  return "<read>";
}

TEST(DamagedStore, OffsetsThatDecreaseAreRefusedNamingTheFrame) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "damaged.h5";
  write_damageable_store(path);
  ASSERT_EQ(store_refusal(path), "<read>");
  // Frame 1's points are rows 3..6 of /points: its first diagram now claims rows 3..500, while the
  // last offset, the one a writer stopped short would leave too large, still fits.
  overwrite_store_row(path, "offsets", 1, {3, 500, 5, 6, 6});
  std::string why = store_refusal(path);
  EXPECT_EQ(why.rfind(path.string() + ": row 1 (frame 1): ", 0), 0u) << why;
  EXPECT_NE(why.find("offsets not ascending"), std::string::npos) << why;
  fs::remove(path);
  write_damageable_store(path);
  overwrite_store_row(path, "network_offsets", 1, {6, 3, 2, 4});  // its grains end before they begin
  why = store_refusal(path);
  EXPECT_EQ(why.rfind(path.string() + ": row 1 (frame 1): ", 0), 0u) << why;
  EXPECT_NE(why.find("network_offsets not ordered"), std::string::npos) << why;
}

TEST(DamagedStore, MetadataFailingItsChecksumIsRefusedInSecondsNamingTheFile) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "damaged.h5";
  write_damageable_store(path);
  haddr_t header = 0;  // the object header of dataset "offsets", checksummed in the latest format
  {
    h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open");
    H5O_info_t info{};
    h5::check(H5Oget_info_by_name2(file.get(), "offsets", &info, H5O_INFO_BASIC, H5P_DEFAULT), "info of offsets");
    header = info.addr;
  }
  ASSERT_EQ(read_store(path).frames.size(), 2u);
  flip_store_byte(path, header + 12);  // inside its first message
  const auto start = std::chrono::steady_clock::now();
  try {
    read_store(path);
    ADD_FAILURE() << "a damaged store was read";
  } catch (const h5::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

}  // namespace
}  // namespace fnet
