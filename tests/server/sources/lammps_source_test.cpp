// LAMMPS dumps read as a run, on small hand-written dumps whose frames are known: one file of many
// snapshots, a file per snapshot by LAMMPS's * pattern, gzip, columns in any order or mapped by
// --columns, wall atoms; every bad dump named by file and line; the force balance; dumps followed
// while they are written.
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include <boost/program_options.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "server/sources/lammps_dump.hpp"
#include "tests/server/sources/run_reading.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::sources {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::unique_ptr<FrameSource> open_source(const fs::path& dir, std::vector<std::string> args) {
  return testing::open_run_source(dir, std::move(args));
}

std::vector<RunFrame> read_run(const fs::path& dir, const std::vector<std::string>& args) {
  return testing::read_run_frames(dir, args);
}

std::string what_of(const fs::path& dir, const std::vector<std::string>& args) { return testing::run_error(dir, args); }

std::string header(const std::string& item, std::uint64_t step, std::size_t rows) {
  return "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF " + item + "\n" + std::to_string(rows) +
         "\nITEM: BOX BOUNDS ff ff pp\n-1 2\n-2 2\n-0.5 0.5\n";
}

// Grains 10 (0,0), 20 (1,0), 30 (0.5,0.8) of radius 0.5 and wall atom 40 (type 3) under grain 10;
// the rows in the order given.
std::string atoms(std::uint64_t step, const std::vector<int>& order = {10, 20, 30, 40}) {
  std::string out = header("ATOMS", step, order.size()) + "ITEM: ATOMS id type x y z radius vx\n";
  for (const int id : order) {
    if (id == 10) out += "10 1 0 0 0 0.5 0.1\n";
    if (id == 20) out += "20 1 1 0 0 0.5 0.1\n";
    if (id == 30) out += "30 2 0.5 0.8 0 0.5 0.1\n";
    if (id == 40) out += "40 3 0 -1 0 0.5 0\n";
  }
  return out;
}

// The pair forces of the documented lines (normal vector, tangential vector, on the first atom),
// scaled by `s`: 10-20 pushes with 2 (tangential 0.5), 30-10 with 1 (none), the wall 40 pushes
// grain 10 with 3 (tangential 0.25).
std::string pairs(std::uint64_t step, double s = 1) {
  const double c = 0.5 / std::hypot(0.5, 0.8), d = 0.8 / std::hypot(0.5, 0.8);
  char rows[512];
  std::snprintf(rows, sizeof rows, "10 20 %.17g 0 0 0 %.17g 0\n30 10 %.17g %.17g 0 0 0 0\n10 40 0 %.17g 0 %.17g 0 0\n",
                -2 * s, 0.5 * s, c * s, d * s, 3 * s, 0.25 * s);
  return header("ENTRIES", step, 3) +
         "ITEM: ENTRIES c_fnet_pair[1] c_fnet_pair[2] c_fnet_force[1] c_fnet_force[2] c_fnet_force[3] "
         "c_fnet_force[4] c_fnet_force[5] c_fnet_force[6]\n" +
         rows;
}

void write_gz(const fs::path& path, const std::string& text) {
  gzFile f = gzopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  gzclose(f);
}

// The frame of atoms() and pairs(step, s) with walls of type 3.
void expect_known_frame(const RunFrame& f, std::uint64_t step, double s) {
  EXPECT_EQ(f.header.step, step);
  ASSERT_EQ(f.frame.particle_count, 3u);
  EXPECT_NEAR(f.frame.particles[0].x, 0, 1e-12);
  EXPECT_NEAR(f.frame.particles[1].x, 1, 1e-12);
  EXPECT_NEAR(f.frame.particles[2].y, 0.8, 1e-12);
  ASSERT_EQ(f.frame.contacts.size(), 2u);
  EXPECT_EQ(f.frame.contacts[0].i, 0);
  EXPECT_EQ(f.frame.contacts[0].j, 1);
  EXPECT_NEAR(f.frame.contacts[0].fn, 2 * s, 1e-12);
  EXPECT_NEAR(f.frame.contacts[0].ft, 0.5 * s, 1e-12);
  EXPECT_EQ(f.frame.contacts[1].i, 2);
  EXPECT_EQ(f.frame.contacts[1].j, 0);
  EXPECT_NEAR(f.frame.contacts[1].fn, s, 1e-12);
  EXPECT_NEAR(f.frame.contacts[1].ft, 0, 1e-12);
  ASSERT_EQ(f.wall_contacts.size(), 1u);
  EXPECT_EQ(f.wall_contacts[0].particle, 0u);
  EXPECT_NEAR(f.wall_contacts[0].fn, 3 * s, 1e-12);
  EXPECT_NEAR(f.wall_contacts[0].ft, 0.25 * s, 1e-12);
  EXPECT_DOUBLE_EQ(f.header.z, 2.0 * 2 / 3);
  // x: the box, -1..2; y: from the wall's top at -0.5 to the box's top at 2.
  EXPECT_DOUBLE_EQ(f.header.rho, 3 * std::numbers::pi * 0.25 / (3 * 2.5));
}

TEST(LammpsSource, OneFileOfManySnapshots) {
  testing::TempDir dir;
  dir.write("atoms.txt", atoms(200, {30, 40, 20, 10}) + atoms(100));
  dir.write("pairs.txt", pairs(100) + pairs(200, 2));
  const auto frames =
      read_run(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--wall-types", "3"});
  ASSERT_EQ(frames.size(), 2u);
  expect_known_frame(frames[0], 100, 1);
  expect_known_frame(frames[1], 200, 2);
  EXPECT_EQ(frames[1].header.index, 1u);
  EXPECT_EQ(frames[1].frame.label, frame_label("lmp", 1));
}

TEST(LammpsSource, AFilePerSnapshotByPatternCompressedOrNot) {
  testing::TempDir dir;
  dir.write("atoms.100.txt", atoms(100));
  write_gz(dir.path() / "atoms.1000.txt.gz", atoms(1000));
  dir.write("pairs.100.txt", pairs(100));
  write_gz(dir.path() / "pairs.1000.txt.gz", pairs(1000, 3));
  const auto frames =
      read_run(dir.path(), {"--lammps-atoms", "@atoms.*.txt*", "--lammps-pairs", "@pairs.*", "--wall-types", "3"});
  ASSERT_EQ(frames.size(), 2u);
  expect_known_frame(frames[0], 100, 1);
  expect_known_frame(frames[1], 1000, 3);
}

TEST(LammpsSource, ColumnsInAnyOrderOrNamedByColumns) {
  testing::TempDir dir;
  dir.write("atoms.txt",
            header("ATOMS", 5, 4) +
                "ITEM: ATOMS diameter ys type xs id\n1 0.5 1 0.3333333333333333 10\n1 0.5 1 0.6666666666666666 20\n"
                "1 0.7 2 0.5 30\n1 0.25 3 0.3333333333333333 40\n");
  // Magnitudes: fn signed, ft's magnitude taken.
  dir.write("pairs.txt", header("ENTRIES", 5, 3) + "ITEM: ENTRIES n t b a\n2 -0.5 20 10\n1 0 10 30\n3 0.25 40 10\n");
  const auto frames = read_run(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt",
                                            "--wall-types", "3", "--columns", "i=a,j=b,fn=n,ft=t"});
  ASSERT_EQ(frames.size(), 1u);
  expect_known_frame(frames[0], 5, 1);
  // The total force on i, split along the line of centres.
  dir.write("total.txt",
            header("ENTRIES", 5, 3) + "ITEM: ENTRIES i j fx fy\n10 20 -2 0.5\n20 10 2 -0.5\n10 40 0.25 3\n");
  const auto total = read_run(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@total.txt",
                                           "--wall-types", "3", "--columns", "i=i,j=j,fx=fx,fy=fy"});
  ASSERT_EQ(total[0].frame.contacts.size(), 1u) << "a pair listed twice counts once";
  EXPECT_NEAR(total[0].frame.contacts[0].fn, 2, 1e-12);
  EXPECT_NEAR(total[0].frame.contacts[0].ft, 0.5, 1e-12);
  EXPECT_NEAR(total[0].wall_contacts[0].fn, 3, 1e-12);
  EXPECT_NEAR(total[0].wall_contacts[0].ft, 0.25, 1e-12);
}

TEST(LammpsSource, PeriodicBoxIsTheRegionAndTheLineOfCentresCrossesIt) {
  testing::TempDir dir;
  const std::string box = "ITEM: BOX BOUNDS pp pp pp\n0 4\n0 2\n-0.5 0.5\n";
  dir.write("atoms.txt", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n" + box +
                             "ITEM: ATOMS id x y radius\n1 0.4 1 0.5\n2 3.7 1 0.5\n");
  // The force on 1 points away from 2's image at -0.3: +x.
  dir.write("pairs.txt",
            "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n1\n" + box + "ITEM: ENTRIES p q f1 f2\n1 2 1.5 0.2\n");
  const auto frames = read_run(
      dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--columns", "i=p,j=q,fx=f1,fy=f2"});
  EXPECT_NEAR(frames[0].frame.contacts[0].fn, 1.5, 1e-12);
  EXPECT_NEAR(frames[0].frame.contacts[0].ft, 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(frames[0].header.rho, 2 * std::numbers::pi * 0.25 / 8);
  EXPECT_DOUBLE_EQ(frames[0].header.z, 1.0);
}

TEST(LammpsSource, BadDumpsAreNamedByFileAndLine) {
  testing::TempDir dir;
  const fs::path d = dir.path();
  dir.write("atoms.txt", atoms(100));
  dir.write("pairs.txt", pairs(100));
  const auto run = [&](const std::string& a, const std::string& p,
                       std::vector<std::string> more = {"--wall-types", "3"}) {
    std::vector<std::string> args{"--lammps-atoms", "@" + a, "--lammps-pairs", "@" + p};
    args.insert(args.end(), more.begin(), more.end());
    return what_of(d, args);
  };
  const std::string a = (d / "atoms.txt").string(), p = (d / "pairs.txt").string();
  // A snapshot cut short: 1 of its 4 rows, named by the last line the file holds.
  const std::string whole = atoms(100);
  dir.write("cut.txt", whole.substr(0, whole.find("20 1 1")));
  EXPECT_THAT(run("cut.txt", "pairs.txt"),
              AllOf(HasSubstr((d / "cut.txt").string() + ":10:"), HasSubstr("ends after 1 of its 4 rows")));
  // A count of rows no memory could hold (past 2^63), the rows missing: cut short, not a failed
  // allocation.
  std::string huge = whole;
  huge.replace(huge.find("ATOMS\n4\n") + 6, 1, "10666666666666666666");
  dir.write("huge.txt", huge);
  EXPECT_THAT(run("huge.txt", "pairs.txt"), HasSubstr("ends after 4 of its 10666666666666666666 rows"));
  // A row cut short.
  dir.write("short.txt", whole.substr(0, whole.size() - 4));
  EXPECT_THAT(run("short.txt", "pairs.txt"),
              AllOf(HasSubstr((d / "short.txt").string() + ":13:"), HasSubstr("6 values under 7 columns")));
  // A compressed file cut short.
  write_gz(d / "cut.txt.gz", atoms(100) + atoms(200));
  {
    const auto size = fs::file_size(d / "cut.txt.gz");
    fs::resize_file(d / "cut.txt.gz", size - 12);
  }
  EXPECT_THAT(run("cut.txt.gz", "pairs.txt"), HasSubstr((d / "cut.txt.gz").string() + ":"));
  // A column missing.
  std::string no_radius = whole;
  no_radius.replace(no_radius.find("radius"), 6, "rad");
  dir.write("noradius.txt", no_radius);
  EXPECT_THAT(run("noradius.txt", "pairs.txt"),
              AllOf(HasSubstr((d / "noradius.txt").string() + ":9:"), HasSubstr("no column radius or diameter")));
  EXPECT_THAT(run("atoms.txt", "pairs.txt", {"--wall-types", "3", "--columns", "i=a,j=b,fn=n,ft=t"}),
              AllOf(HasSubstr(p + ":9:"), HasSubstr("no column a")));
  // An id the per-atom dump does not hold.
  std::string stranger = pairs(100);
  stranger.replace(stranger.find("\n30 10 "), 7, "\n31 10 ");
  dir.write("stranger.txt", stranger);
  EXPECT_THAT(run("atoms.txt", "stranger.txt"),
              AllOf(HasSubstr((d / "stranger.txt").string() + ":11:"), HasSubstr("atom id 31 is not in")));
  // NaN.
  std::string nan = atoms(100);
  nan.replace(nan.find("1 1 0 0 0.5"), 11, "1 nan 0 0 0.5");
  dir.write("nan.txt", nan);
  EXPECT_THAT(run("nan.txt", "pairs.txt"),
              AllOf(HasSubstr((d / "nan.txt").string() + ":11:"), HasSubstr("column x is not a finite number")));
  // A TIMESTEP without its partner, either way.
  dir.write("more_atoms.txt", atoms(100) + atoms(300));
  EXPECT_THAT(run("more_atoms.txt", "pairs.txt"), AllOf(HasSubstr((d / "more_atoms.txt").string() + ":14:"),
                                                        HasSubstr("TIMESTEP 300 has no snapshot in the pair dumps")));
  dir.write("more_pairs.txt", pairs(100) + pairs(50));
  EXPECT_THAT(run("atoms.txt", "more_pairs.txt"),
              AllOf(HasSubstr((d / "more_pairs.txt").string() + ":13:"),
                    HasSubstr("TIMESTEP 50 has no snapshot in the per-atom dumps")));
  // Other dumps that are not what they should be.
  EXPECT_THAT(run("pairs.txt", "pairs.txt"), AllOf(HasSubstr(p + ":3:"), HasSubstr("a local dump where")));
  std::string triclinic = whole;
  triclinic.replace(triclinic.find("ff ff pp"), 8, "xy xz yz ff ff pp");
  dir.write("triclinic.txt", triclinic);
  EXPECT_THAT(run("triclinic.txt", "pairs.txt"),
              AllOf(HasSubstr((d / "triclinic.txt").string() + ":5:"), HasSubstr("triclinic")));
  EXPECT_THAT(run("none.*.txt", "pairs.txt"), HasSubstr("none.*.txt: no file matches"));
  // A grain of the first frame missing from a later one.
  dir.write("lost.txt", atoms(100) + atoms(200, {10, 20, 40}));
  dir.write("pairs2.txt", pairs(100) + pairs(200));
  EXPECT_THAT(run("lost.txt", "pairs2.txt"),
              AllOf(HasSubstr((d / "lost.txt").string() + ":14:"), HasSubstr("atom id 30 of the first frame")));
}

TEST(LammpsSource, UsageErrorsNameTheFlag) {
  testing::TempDir dir;
  dir.write("atoms.txt", atoms(100));
  dir.write("pairs.txt", pairs(100));
  const std::vector<std::string> base{"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt"};
  const auto with = [&](std::vector<std::string> more) {
    more.insert(more.begin(), base.begin(), base.end());
    return what_of(dir.path(), more);
  };
  EXPECT_THAT(with({"--columns", "i=a,fn=b"}), HasSubstr("--columns: the normal and the tangential force"));
  EXPECT_THAT(with({"--columns", "i=a,q=b"}), HasSubstr("--columns: unknown role q"));
  EXPECT_THAT(with({"--columns", "fx=a,fy=b,fn=c"}), HasSubstr("--columns: fx, fy, fz go without fn"));
  EXPECT_THAT(with({"--wall-types", "3,x"}), HasSubstr("--wall-types: \"x\" is not an atom type"));
  EXPECT_THAT(with({"--check-balance", "-1"}), HasSubstr("--check-balance: \"-1\" is not a positive number"));
}

// Two grains pressed together between two wall atoms: every grain balanced.
TEST(LammpsSource, ForceBalanceCatchesAColumnReadAsTheWrongQuantity) {
  testing::TempDir dir;
  const std::string box = "ITEM: BOX BOUNDS ff ff pp\n-2 3\n-1 1\n-0.5 0.5\n";
  dir.write("atoms.txt", "ITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n4\n" + box +
                             "ITEM: ATOMS id type x y radius\n1 1 0 0 0.5\n2 1 1 0 0.5\n3 2 -1 0 0.5\n4 2 2 0 0.5\n");
  dir.write("pairs.txt",
            "ITEM: TIMESTEP\n7\nITEM: NUMBER OF ENTRIES\n3\n" + box +
                "ITEM: ENTRIES i j fnx fny ftx fty e\n1 2 -2 0 0 0.1 1\n3 1 -2 0 0 0.1 2\n2 4 -2 0 0 0.1 3\n");
  const std::vector<std::string> args{"--lammps-atoms", "@atoms.txt", "--lammps-pairs",  "@pairs.txt",
                                      "--wall-types",   "2",          "--check-balance", "0.01"};
  const auto with = [&](const std::string& columns) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"--columns", columns});
    return a;
  };
  EXPECT_EQ(read_run(dir.path(), with("i=i,j=j,fnx=fnx,fny=fny,ftx=ftx,fty=fty")).size(), 1u);
  // Another quantity (e) read as the normal force's x component: neither grain balanced.
  const fs::path atoms_file = dir.path() / "atoms.txt";
  EXPECT_THAT(what_of(dir.path(), with("i=i,j=j,fnx=e,fny=fny,ftx=ftx,fty=fty")),
              AllOf(HasSubstr(atoms_file.string() + ":1: timestep 7: 2 of 2 grains out of force balance"),
                    HasSubstr("worst: atom id")));
  EXPECT_THAT(what_of(dir.path(), with("i=i,j=j,fn=fnx,ft=fty")),
              HasSubstr("--check-balance: the force balance needs"));
}

void append(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::app) << text; }

// A dump written a byte at a time: each snapshot is read once its last row's newline is there, not
// a byte before (a row cut inside a number has the right count of values), and read as the whole
// file reads it.
TEST(LammpsFollow, ASnapshotIsReadOnceWholeAndNotBefore) {
  testing::TempDir dir;
  const std::string first = atoms(100), text = first + atoms(200, {40, 30, 20, 10});
  const fs::path path = dir.path() / "atoms.txt";
  dir.write("atoms.txt", "");
  DumpTail tail(path, DumpKind::atoms);
  std::vector<DumpSnapshot> read;
  for (std::size_t cut = 1; cut <= text.size(); ++cut) {
    append(path, text.substr(cut - 1, 1));
    std::vector<DumpSnapshot> got = tail.read_new();
    ASSERT_EQ(got.size(), cut == first.size() || cut == text.size() ? 1u : 0u) << "after " << cut << " bytes";
    for (DumpSnapshot& s : got) read.push_back(std::move(s));
  }
  const std::vector<DumpSnapshot> whole = read_dump(path, DumpKind::atoms);
  ASSERT_EQ(read.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(read[k].timestep, whole[k].timestep);
    EXPECT_EQ(read[k].line, whole[k].line);
    EXPECT_EQ(read[k].values, whole[k].values);
  }
  EXPECT_NO_THROW(tail.require_read());
}

// Frames while the dumps are written, a file per snapshot: each once both its snapshots are whole
// (a pair dump half-written holds its frame back), until the log says the run finished.
TEST(LammpsFollow, FramesAsTheyAreWrittenUntilTheLogSaysTheRunFinished) {
  using namespace std::chrono_literals;
  testing::TempDir dir;
  const std::string p100 = pairs(100);
  std::thread writer([&] {
    std::this_thread::sleep_for(100ms);
    dir.write("atoms.100.txt", atoms(100));
    dir.write("pairs.100.txt", p100.substr(0, p100.size() - 20));
    std::this_thread::sleep_for(300ms);
    append(dir.path() / "pairs.100.txt", p100.substr(p100.size() - 20));
    std::this_thread::sleep_for(300ms);
    dir.write("atoms.200.txt", atoms(200, {20, 40, 10, 30}));
    dir.write("pairs.200.txt", pairs(200, 2));
    dir.write("log.lammps", "Loop time of 1 on 1 procs\n\nTotal wall time: 0:00:01\n");
  });
  const auto started = std::chrono::steady_clock::now();
  const auto source = open_source(dir.path(), {"--lammps-atoms", "@atoms.*.txt", "--lammps-pairs", "@pairs.*.txt",
                                               "--wall-types", "3", "--follow", "--lammps-log", "@log.lammps"});
  EXPECT_GE(std::chrono::steady_clock::now() - started, 400ms) << "the first frame before its pair dump was whole";
  EXPECT_EQ(source->announcement().particles, 3u);
  EXPECT_EQ(source->announcement().frames, 0u);
  std::vector<RunFrame> frames;
  while (auto f = source->next()) frames.push_back(std::move(*f));
  writer.join();
  ASSERT_EQ(frames.size(), 2u);
  expect_known_frame(frames[0], 100, 1);
  expect_known_frame(frames[1], 200, 2);
  EXPECT_LT(std::chrono::steady_clock::now() - started, 10s) << "the end the log says was not seen";
}

// A run that stopped while writing: after the idle timeout, every whole frame, then the snapshot
// cut short named by its file and line.
TEST(LammpsFollow, ASnapshotLeftCutShortIsNamedAfterTheFramesBeforeIt) {
  testing::TempDir dir;
  const std::string a200 = atoms(200);
  dir.write("atoms.txt", atoms(100) + a200.substr(0, a200.size() - 30));
  dir.write("pairs.txt", pairs(100) + pairs(200));
  const auto source = open_source(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt",
                                               "--wall-types", "3", "--follow", "--idle-timeout", "0.3"});
  const auto first = source->next();
  ASSERT_TRUE(first);
  expect_known_frame(*first, 100, 1);
  try {
    source->next();
    ADD_FAILURE() << "no error for the snapshot cut short";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("atoms.txt:"), HasSubstr("cut short")));
  }
}

TEST(LammpsFollow, UsageErrors) {
  testing::TempDir dir;
  dir.write("atoms.txt", atoms(100));
  dir.write("pairs.txt", pairs(100));
  EXPECT_THAT(
      what_of(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--idle-timeout", "5"}),
      HasSubstr("--idle-timeout needs --follow"));
  EXPECT_THAT(what_of(dir.path(), {"--lammps-atoms", "@atoms.txt.gz", "--lammps-pairs", "@pairs.txt", "--follow"}),
              HasSubstr("plain-text"));
  EXPECT_THAT(what_of(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--follow",
                                   "--idle-timeout", "soon"}),
              HasSubstr("--idle-timeout"));
  // --rho log: names the log and the column; the log is read when the run opens.
  const std::vector<std::string> base{"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt"};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return what_of(dir.path(), args);
  };
  EXPECT_THAT(with({"--rho", "log:log.lammps"}), HasSubstr("is not log:PATH:COLUMN or column:NAME"));
  EXPECT_THAT(with({"--rho", "@log.lammps:v_rho"}), HasSubstr("is not log:PATH:COLUMN or column:NAME"));
  dir.write("log.lammps", "Step Temp\n0 1\nLoop time of 1\n");
  EXPECT_THAT(with({"--rho", "log:" + (dir.path() / "log.lammps").string() + ":v_rho"}),
              HasSubstr("no thermo output names v_rho"));
  dir.write("log.lammps", "Step v_rho\n0 0.8\nLoop time of 1\n");
  EXPECT_THAT(with({"--rho", "log:" + (dir.path() / "log.lammps").string() + ":v_rho"}),
              AllOf(HasSubstr("atoms.txt:1: TIMESTEP 100 has no thermo row"), HasSubstr("log.lammps:v_rho")));
  EXPECT_THAT(with({"--rho", "log:" + (dir.path() / "log.lammps").string() + ":v_rho", "--follow"}),
              HasSubstr("does not go with --follow"));
}

// --rho column:NAME: a per-atom column of one value per snapshot is the frame's ρ, followed or not;
// a column that varies from row to row is refused, naming the row.
TEST(LammpsSource, RhoFromAColumnOfOneValue) {
  testing::TempDir dir;
  const auto with_rho = [](std::string text, const std::vector<std::string>& values) {
    text.replace(text.find("vx\n"), 3, "vx v_rho\n");
    std::size_t at = text.find("vx v_rho\n") + 9;
    for (const std::string& v : values) {
      at = text.find('\n', at);
      text.insert(at, " " + v);
      at += v.size() + 2;
    }
    return text;
  };
  dir.write("atoms.txt", with_rho(atoms(100), {"0.625", "0.625", "0.625", "0.625"}) +
                             with_rho(atoms(200), {"0.75", "0.75", "0.75", "0.75"}));
  dir.write("pairs.txt", pairs(100) + pairs(200, 2));
  for (const bool follow : {false, true}) {
    std::vector<std::string> args{"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt",
                                  "--wall-types",   "3",          "--rho",          "column:v_rho"};
    if (follow) args.insert(args.end(), {"--follow", "--idle-timeout", "0.2"});
    const auto frames = read_run(dir.path(), args);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].header.rho, 0.625);
    EXPECT_EQ(frames[1].header.rho, 0.75);
  }
  dir.write("varies.txt", with_rho(atoms(100), {"0.625", "0.625", "0.5", "0.625"}));
  dir.write("pairs100.txt", pairs(100));
  EXPECT_THAT(what_of(dir.path(), {"--lammps-atoms", "@varies.txt", "--lammps-pairs", "@pairs100.txt", "--rho",
                                   "column:v_rho", "--wall-types", "3"}),
              AllOf(HasSubstr("varies.txt:12:"), HasSubstr("not one finite value")));
  EXPECT_THAT(what_of(dir.path(), {"--lammps-atoms", "@atoms.txt", "--lammps-pairs", "@pairs.txt", "--rho",
                                   "column:v_phi", "--wall-types", "3"}),
              HasSubstr("no column v_phi"));
}

}  // namespace
}  // namespace fnet::sources
