// A store damaged on disk is refused promptly, naming the file: a piece of metadata that fails its
// checksum is read h5::kSwmrReadAttempts times, not HDF5's default of a hundred times with longer
// and longer sleeps, meant for a writer caught mid-flush, which held a server's start for minutes.
#include <chrono>
#include <fstream>

#include <gtest/gtest.h>

#include "common/store/analysis_store.hpp"
#include "common/store/hdf5_io.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

namespace fs = std::filesystem;

// Flips every bit of the byte at `offset` of the file.
void flip_byte(const fs::path& path, std::uint64_t offset) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  const char byte = static_cast<char>(~file.get());
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(byte);
}

TEST(DamagedStore, MetadataFailingItsChecksumIsRefusedInSecondsNamingTheFile) {
  testing::TempDir dir;
  const fs::path path = dir.path() / "damaged.h5";
  {
    StoreWriter w(path, "damaged");
    AnalyzedFrame f;
    f.header = {"damaged", 0, 0, 0.0, 0.7, 3.5};
    f.diagrams.normal.pd1 = {{2.0, 1.0}};
    w.append(f);
  }
  haddr_t header = 0;  // the object header of dataset "offsets", checksummed in the latest format
  {
    h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open");
    H5O_info_t info{};
    h5::check(H5Oget_info_by_name2(file.get(), "offsets", &info, H5O_INFO_BASIC, H5P_DEFAULT), "info of offsets");
    header = info.addr;
  }
  ASSERT_EQ(read_store(path).frames.size(), 1u);
  flip_byte(path, header + 12);  // inside its first message
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
