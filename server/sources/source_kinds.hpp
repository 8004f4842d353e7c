// The kinds of input, and which commands take which. Each kind is a file of its own, named after
// it, holding its FrameSource and its flags. A new kind is that file, its declaration here and its
// place in the lists below of the commands that take it, and its line in CMakeLists.txt: in
// fnet_sources, or in fnet_sources_hdf5 if it reads HDF5, which fnet-analyze does not load.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "server/sources/source_kind.hpp"

namespace fnet::sources {

SourceKind frame_files_kind();  // --contacts C.csv [--particles P.csv]: one frame (frame_files_source.cpp)
SourceKind csv_run_kind();      // --csv-dir DIR: the folder fnet-simd --export-csv writes (csv_run_source.cpp)
SourceKind run_file_kind();     // --run-file F: the HDF5 run file (run_file_source.cpp, in fnet_sources_hdf5)
SourceKind lammps_kind();       // --lammps-atoms P --lammps-pairs P: LAMMPS dumps (lammps_source.cpp)
// --lammps-atoms F --lammps-pairs F [--timestep N]: one frame of them (lammps_frame_source.cpp)
SourceKind lammps_frame_kind();

// One frame: diagram (explain reads two of the same kinds).
inline std::vector<SourceKind> frame_kinds() { return {frame_files_kind(), lammps_frame_kind()}; }
// A whole run: store and publish, in fnet-analyze-io (the run file's kind needs fnet_sources_hdf5).
inline std::vector<SourceKind> run_kinds() { return {run_file_kind(), csv_run_kind(), lammps_kind()}; }

// The frame-files kind for a command whose arguments name the files themselves (explain's A.csv
// B.csv): the frame is labelled by the contacts file; without particles its particle count is the
// largest contact index + 1.
std::unique_ptr<FrameSource> open_frame_files(const std::filesystem::path& contacts,
                                              const std::optional<std::filesystem::path>& particles);

}  // namespace fnet::sources
