// The CSV reader: what it accepts (any column order, extra columns, CRLF) and how it refuses
// (every error names the file and, where a line is at fault, the line).
#include "common/codec/frame_csv.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <sys/stat.h>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/codec/run_csv.hpp"
#include "tests/common/codec/csv_error.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet {
namespace {

using fnet::testing::TempDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

using fnet::testing::csv_error;

// path:line, as the reader prefixes messages about one line.
std::string at(const std::filesystem::path& file, int line) { return file.string() + ":" + std::to_string(line) + ":"; }

bool same_contact(const Contact& a, const Contact& b) {
  return a.i == b.i && a.j == b.j && a.fn == b.fn && a.ft == b.ft;
}

TEST(FrameCsv, ReadsContactsAndParticles) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fn,ft\n0,1,1.5,0.25\n2,1,-0.125,0\n");
  const auto particles = dir.write("p.csv", "id,x,y,r\n2,5,6,0.5\n0,1,2,0.4\n1,3,4,0.6\n3,7,8,0.45\n");
  const Frame f = read_frame_csv(contacts, particles);
  EXPECT_EQ(f.label, contacts.string());
  EXPECT_EQ(f.particle_count, 4u);
  ASSERT_EQ(f.contacts.size(), 2u);
  EXPECT_TRUE(same_contact(f.contacts[0], {0, 1, 1.5, 0.25}));
  EXPECT_TRUE(same_contact(f.contacts[1], {2, 1, -0.125, 0}));
  ASSERT_EQ(f.particles.size(), 4u);  // rows land at their id, whatever the row order
  EXPECT_EQ(f.particles[0].x, 1);
  EXPECT_EQ(f.particles[2].r, 0.5);
  EXPECT_EQ(f.particles[3].y, 8);
}

TEST(FrameCsv, WithoutParticlesTheCountIsTheLargestIndexPlusOne) {
  TempDir dir;
  const Frame f = read_frame_csv(dir.write("c.csv", "i,j,fn,ft\n3,9,1,1\n4,2,1,1\n"), std::nullopt);
  EXPECT_EQ(f.particle_count, 10u);
  EXPECT_TRUE(f.particles.empty());
}

TEST(FrameCsv, ColumnsInAnotherOrderAndExtraColumnsWork) {
  TempDir dir;
  const auto contacts = read_contacts_csv(dir.write("c.csv", "ft,extra,j,fn,i\n0.25,x,1,1.5,0\n0,y,7,-2,3\n"));
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_TRUE(same_contact(contacts[0], {0, 1, 1.5, 0.25}));
  EXPECT_TRUE(same_contact(contacts[1], {3, 7, -2, 0}));
  const auto particles = read_particles_csv(dir.write("p.csv", "r,y,x,id\n0.5,2,1,1\n0.25,4,3,0\n"));
  ASSERT_EQ(particles.size(), 2u);
  EXPECT_EQ(particles[0].x, 3);
  EXPECT_EQ(particles[0].y, 4);
  EXPECT_EQ(particles[0].r, 0.25);
  EXPECT_EQ(particles[1].r, 0.5);
}

TEST(FrameCsv, CrlfLineEndingsWork) {
  TempDir dir;
  const auto contacts = read_contacts_csv(dir.write("c.csv", "i,j,fn,ft\r\n0,1,1.5,0.25\r\n2,1,-0.125,3\r\n"));
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_TRUE(same_contact(contacts[1], {2, 1, -0.125, 3}));  // the last field would carry '\r'
  const auto particles = read_particles_csv(dir.write("p.csv", "id,x,y,r\r\n1,3,4,0.6\r\n0,1,2,0.4\r\n"));
  ASSERT_EQ(particles.size(), 2u);
  EXPECT_EQ(particles[1].r, 0.6);
}

TEST(FrameCsv, MissingFileNamesTheFile) {
  TempDir dir;
  const auto missing = dir.path() / "no_such_contacts.csv";
  EXPECT_THAT(csv_error([&] { read_contacts_csv(missing); }),
              AllOf(HasSubstr(missing.string()), HasSubstr("cannot open")));
  EXPECT_THAT(csv_error([&] { read_frame_csv(dir.write("c.csv", "i,j,fn,ft\n"), dir.path() / "no_p.csv"); }),
              HasSubstr((dir.path() / "no_p.csv").string()));
}

TEST(FrameCsv, MissingHeaderColumnNamesFileLineAndColumn) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fn\n0,1,2\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(contacts); }), AllOf(HasSubstr(at(contacts, 1)), HasSubstr("'ft'")));
  const auto particles = dir.write("p.csv", "\nid,x,r\n0,1,2\n");  // a blank first line: the header is line 2
  EXPECT_THAT(csv_error([&] { read_particles_csv(particles); }), AllOf(HasSubstr(at(particles, 2)), HasSubstr("'y'")));
}

TEST(FrameCsv, NonNumericFieldNamesFileLineColumnAndText) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fn,ft\n0,1,1,1\n1,2,abc,0.5\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(contacts); }),
              AllOf(HasSubstr(at(contacts, 3)), HasSubstr("'fn'"), HasSubstr("'abc'")));
  const auto fractional_index = dir.write("c2.csv", "i,j,fn,ft\n0,1.5,1,1\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(fractional_index); }),
              AllOf(HasSubstr(at(fractional_index, 2)), HasSubstr("'j'"), HasSubstr("'1.5'")));
  const auto empty_field = dir.write("p.csv", "id,x,y,r\n0,1,,0.5\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(empty_field); }),
              AllOf(HasSubstr(at(empty_field, 2)), HasSubstr("'y'")));
  const auto trailing = dir.write("p2.csv", "id,x,y,r\n0,1,2,0.5x\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(trailing); }), AllOf(HasSubstr(at(trailing, 2)), HasSubstr("'r'")));
}

// An exported run folder whose index has a non-numeric field: the message quotes the whole row.
TEST(RunCsv, BadIndexRowIsQuotedWhole) {
  TempDir dir;
  const auto index = dir.write("index.csv", "frame,step,time,rho,Z\n0,12,abc,0.5,4\n");
  EXPECT_THAT(csv_error([&] { read_csv_run(dir.path(), "r"); }),
              AllOf(HasSubstr(at(index, 2)), HasSubstr("'0,12,abc,0.5,4'")));
}

// Z is `z` in fnet-simd's index.csv and every fnet CSV; the LAMMPS reference data says `Z`: both read.
TEST(RunCsv, IndexReadsZUnderEitherName) {
  for (const char* name : {"z", "Z"}) {
    TempDir dir;
    dir.write("index.csv", std::string("frame,step,time,rho,") + name + "\n7,120,0.5,0.8125,3.0000000000000004\n");
    dir.write("frame_0007_contacts.csv", "i,j,fn,ft\n0,1,1,0.5\n");
    dir.write("frame_0007_particles.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n");
    const std::vector<RunFrame> frames = read_csv_run(dir.path(), "r");
    ASSERT_EQ(frames.size(), 1u) << name;
    EXPECT_EQ(frames[0].header.index, 7u);
    EXPECT_EQ(frames[0].header.step, 120u);
    EXPECT_EQ(frames[0].header.time, 0.5);
    EXPECT_EQ(frames[0].header.rho, 0.8125);
    EXPECT_EQ(frames[0].header.z, 3.0000000000000004) << name;
  }
  TempDir neither;
  const auto index = neither.write("index.csv", "frame,step,rho\n0,0,0.5\n");
  EXPECT_THAT(csv_error([&] { read_csv_run(neither.path(), "r"); }), AllOf(HasSubstr(at(index, 1)), HasSubstr("'z'")));
}

// An experiment's frames have no simulation step: index.csv without `step` reads, each frame's
// step its index; a missing frame or rho column is still an error naming it.
TEST(RunCsv, IndexWithoutStepTakesTheFrameIndex) {
  TempDir dir;
  dir.write("index.csv", "frame,rho,z\n3,0.8,4\n");
  dir.write("frame_0003_contacts.csv", "i,j,fn,ft\n0,1,1,0.5\n");
  dir.write("frame_0003_particles.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n");
  const std::vector<RunFrame> frames = read_csv_run(dir.path(), "r");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].header.step, 3u);
  EXPECT_EQ(frames[0].header.time, 0.0);
  TempDir no_rho;
  const auto index = no_rho.write("index.csv", "frame,z\n0,1\n");
  EXPECT_THAT(csv_error([&] { read_csv_run(no_rho.path(), "r"); }), AllOf(HasSubstr(at(index, 1)), HasSubstr("'rho'")));
}

// A '+' may lead a number; a second sign after it does not make one.
TEST(FrameCsv, PlusFollowedByMinusIsNotANumber) {
  TempDir dir;
  const auto contacts = dir.write("c.csv", "i,j,fn,ft\n0,1,+-2,1\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(contacts); }), AllOf(HasSubstr(at(contacts, 2)), HasSubstr("'fn'")));
  const auto index = dir.write("c2.csv", "i,j,fn,ft\n+-1,1,2,1\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(index); }), AllOf(HasSubstr(at(index, 2)), HasSubstr("'i'")));
}

TEST(FrameCsv, WrongFieldCountNamesFileAndLine) {
  TempDir dir;
  const auto few = dir.write("c.csv", "i,j,fn,ft\n0,1,1,1\n1,2,3\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(few); }),
              AllOf(HasSubstr(at(few, 3)), HasSubstr("expected 4 fields, found 3")));
  const auto many = dir.write("p.csv", "id,x,y,r\n0,1,2,3,4\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(many); }), AllOf(HasSubstr(at(many, 2)), HasSubstr("found 5")));
}

TEST(FrameCsv, EmptyFileIsAnError) {
  TempDir dir;
  const auto empty = dir.write("c.csv", "");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(empty); }), AllOf(HasSubstr(empty.string()), HasSubstr("no header")));
}

// The header of frame_csv.hpp promises "Errors name the file and line" for every error.
TEST(FrameCsv, DuplicateParticleIdNamesFileAndLine) {
  TempDir dir;
  const auto particles = dir.write("p.csv", "id,x,y,r\n0,1,2,0.5\n1,3,4,0.5\n0,5,6,0.5\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(particles); }),
              AllOf(HasSubstr(particles.string()), HasSubstr("id 0"), HasSubstr(at(particles, 4))));
}

TEST(FrameCsv, ParticleIdOutOfRangeNamesFileAndLine) {
  TempDir dir;
  const auto too_large = dir.write("p.csv", "id,x,y,r\n0,1,2,0.5\n3,3,4,0.5\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(too_large); }),
              AllOf(HasSubstr(too_large.string()), HasSubstr("id 3"), HasSubstr(at(too_large, 3))));
  const auto negative = dir.write("p2.csv", "id,x,y,r\n-1,1,2,0.5\n0,3,4,0.5\n");
  EXPECT_THAT(csv_error([&] { read_particles_csv(negative); }),
              AllOf(HasSubstr(negative.string()), HasSubstr("id -1"), HasSubstr(at(negative, 2))));
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

template <class T>
void put(std::string& out, T v) {
  char buf[32];
  out.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

// Numbers written shortest (std::to_chars, as fnet-simd writes them) read back bit for bit: random
// bit patterns (subnormals, huge, tiny), negative zero, -1, and everyday forces and coordinates.
TEST(FrameCsv, EveryDoubleReadsBackBitForBit) {
  std::mt19937_64 rng(77);
  const auto any_double = [&] {
    double v;
    do v = std::bit_cast<double>(rng());
    while (!std::isfinite(v));
    return v;
  };
  std::uniform_real_distribution<double> everyday(-50.0, 50.0);
  std::vector<Contact> contacts;
  std::vector<Particle> particles;
  const double special[] = {0.0,
                            -0.0,
                            -1.0,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            1e-300};
  for (std::int64_t k = 0; k < 5000; ++k) {
    const auto value = [&](int salt) {
      if (k < 8) return special[(k + salt) % 8];
      return (k + salt) % 3 == 0 ? any_double() : everyday(rng);
    };
    contacts.push_back({k, k + 1 + static_cast<std::int64_t>(rng() % 1000), value(0), value(1)});
    particles.push_back({value(2), value(3), value(4)});
  }
  std::string c_text = "i,j,fn,ft\n", p_text = "id,x,y,r\n";
  for (const Contact& c : contacts) {
    put(c_text, c.i), c_text += ',', put(c_text, c.j), c_text += ',', put(c_text, c.fn), c_text += ',';
    put(c_text, c.ft), c_text += '\n';
  }
  for (std::size_t k = particles.size(); k-- > 0;) {  // rows in reverse: ids place them
    const Particle& p = particles[k];
    put(p_text, static_cast<std::int64_t>(k)), p_text += ',', put(p_text, p.x), p_text += ',', put(p_text, p.y);
    p_text += ',', put(p_text, p.r), p_text += '\n';
  }
  TempDir dir;
  const auto read_contacts = read_contacts_csv(dir.write("c.csv", c_text));
  const auto read_particles = read_particles_csv(dir.write("p.csv", p_text));
  ASSERT_EQ(read_contacts.size(), contacts.size());
  ASSERT_EQ(read_particles.size(), particles.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    EXPECT_EQ(read_contacts[k].i, contacts[k].i);
    EXPECT_EQ(read_contacts[k].j, contacts[k].j);
    EXPECT_EQ(bits(read_contacts[k].fn), bits(contacts[k].fn)) << "row " << k;
    EXPECT_EQ(bits(read_contacts[k].ft), bits(contacts[k].ft)) << "row " << k;
    EXPECT_EQ(bits(read_particles[k].x), bits(particles[k].x)) << "particle " << k;
    EXPECT_EQ(bits(read_particles[k].y), bits(particles[k].y)) << "particle " << k;
    EXPECT_EQ(bits(read_particles[k].r), bits(particles[k].r)) << "particle " << k;
  }
}

// Two numbers glued together are one field, not two, though each is a valid number on its own.
TEST(FrameCsv, GluedNumbersAreOneField) {
  TempDir dir;
  const auto glued = dir.write("c.csv", "i,j,fn,ft\n0,1,2.5-0.5\n");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(glued); }),
              AllOf(HasSubstr(at(glued, 2)), HasSubstr("expected 4 fields, found 3")));
}

// A file read whole need not be a regular file: a pipe, of unknown size, is read to its end.
TEST(FrameCsv, ReadsFromAPipe) {
  TempDir dir;
  const auto fifo = dir.path() / "contacts.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string text = "i,j,fn,ft\n";
  for (int k = 0; k < 3000; ++k) text += std::to_string(k) + "," + std::to_string(k + 1) + ",0.5,0.25\n";
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text; });
  const auto contacts = read_contacts_csv(fifo);
  writer.join();
  ASSERT_EQ(contacts.size(), 3000u);
  EXPECT_TRUE(same_contact(contacts[2999], {2999, 3000, 0.5, 0.25}));
}

// Blanks around fields, blank lines (also of spaces and tabs), a last line without its newline:
// read as the line-by-line reader read them.
TEST(FrameCsv, BlanksBlankLinesAndAMissingFinalNewlineWork) {
  TempDir dir;
  const auto contacts =
      read_contacts_csv(dir.write("c.csv", "\n \t\r\n i , j,fn\t,ft \r\n\n  \n0 ,\t1, 1.5 ,0.25\r\n\t\n2,1,-0.125,3"));
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_TRUE(same_contact(contacts[0], {0, 1, 1.5, 0.25}));
  EXPECT_TRUE(same_contact(contacts[1], {2, 1, -0.125, 3}));
}

// A file cut short: the last row has too few fields, or its last number is incomplete; the error
// names the line (and the column when a value is at fault).
TEST(FrameCsv, TruncatedFileNamesTheLastLine) {
  TempDir dir;
  const auto cut_row = dir.write("c.csv", "i,j,fn,ft\n0,1,1,1\n1,2,0.5,0.25\n2,3,1.");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(cut_row); }),
              AllOf(HasSubstr(at(cut_row, 4)), HasSubstr("expected 4 fields, found 3")));
  const auto cut_number = dir.write("p.csv", "id,x,y,r\n0,1,2,0.5\n1,3,4,0.5e");
  EXPECT_THAT(csv_error([&] { read_particles_csv(cut_number); }),
              AllOf(HasSubstr(at(cut_number, 3)), HasSubstr("'r'"), HasSubstr("'0.5e'")));
  const auto cut_header = dir.write("h.csv", "i,j,f");
  EXPECT_THAT(csv_error([&] { read_contacts_csv(cut_header); }),
              AllOf(HasSubstr(at(cut_header, 1)), HasSubstr("'fn'")));
}

// Every column of a row is checked, the last one too, and a value's spaces do not hide garbage.
TEST(FrameCsv, BadNumberInAnyColumnNamesLineAndColumn) {
  TempDir dir;
  const char* columns[] = {"i", "j", "fn", "ft"};
  for (int c = 0; c < 4; ++c) {
    std::string row[4] = {"0", "1", "2.5", "0.5"};
    row[c] = c < 2 ? "1 2" : "2.5.1";
    const auto file =
        dir.write("c.csv", "i,j,fn,ft\n3,4,1,1\n" + row[0] + "," + row[1] + "," + row[2] + "," + row[3] + "\n");
    EXPECT_THAT(csv_error([&] { read_contacts_csv(file); }),
                AllOf(HasSubstr(at(file, 3)), HasSubstr(std::string("'") + columns[c] + "'"), HasSubstr(row[c])))
        << columns[c];
  }
}

}  // namespace
}  // namespace fnet
