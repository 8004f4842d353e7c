// fnet-analyze diagram as users run it: JSON on stdout equal to the library's answer; errors as a
// non-zero exit, a message on stderr that names the problem, and nothing on stdout.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/codec/diagram_gudhi.hpp"
#include "common/codec/diagram_json.hpp"
#include "common/codec/frame_csv.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/persistence.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::testing {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const std::filesystem::path kFrames = std::filesystem::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";

class DiagramCli : public ::testing::Test {
 protected:
  ProcessResult analyze(std::vector<std::string> args) { return run_process(FNET_ANALYZE, args, scratch_.path()); }
  std::filesystem::path write(const std::string& name, const std::string& text) { return scratch_.write(name, text); }

  // Checks a failed run: non-zero exit, nothing on stdout, and returns stderr.
  std::string failure_message(const std::vector<std::string>& args) {
    const ProcessResult r = analyze(args);
    EXPECT_NE(r.exit_code, 0) << "stdout: " << r.out;
    EXPECT_EQ(r.out, "") << "a failed run must print nothing on stdout";
    EXPECT_NE(r.err, "") << "a failed run must say why on stderr";
    return r.err;
  }

 private:
  TempDir scratch_;
};

// Parses the output and checks it against the library run on the same files.
void expect_same_as_library(const ProcessResult& r, const Frame& frame, ForceKind kind) {
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  nlohmann::json printed;
  ASSERT_NO_THROW(printed = nlohmann::json::parse(r.out)) << r.out.substr(0, 200);
  ASSERT_TRUE(printed.is_object());
  std::vector<std::string> keys;
  for (const auto& item : printed.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(keys, (std::vector<std::string>{"edges", "pd0", "pd1", "triangles", "vertices"}));

  const FrameDiagrams expected = compute_persistence(build_network(frame, kind));
  // JSON numbers are printed to round-trip, so equality is exact.
  EXPECT_TRUE(diagram_from_json(printed.at("pd0")) == expected.pd0);
  EXPECT_TRUE(diagram_from_json(printed.at("pd1")) == expected.pd1);
  EXPECT_EQ(printed.at("vertices").get<std::size_t>(), expected.vertices);
  EXPECT_EQ(printed.at("edges").get<std::size_t>(), expected.edges);
  EXPECT_EQ(printed.at("triangles").get<std::size_t>(), expected.triangles);
}

TEST_F(DiagramCli, LammpsFrameNormalForcesEqualTheLibrary) {
  const auto contacts = kFrames / "frame_0008_contacts.csv", particles = kFrames / "frame_0008_particles.csv";
  const ProcessResult r = analyze({"diagram", "--contacts", contacts.string(), "--particles", particles.string()});
  const Frame frame = read_frame_csv(contacts, particles);
  expect_same_as_library(r, frame, ForceKind::normal);
  const auto printed = nlohmann::json::parse(r.out);
  EXPECT_EQ(printed.at("vertices"), 2000);  // every particle of the table, rattlers included
  EXPECT_FALSE(printed.at("pd1").empty()) << "a jammed frame has loops";
}

TEST_F(DiagramCli, TangentialForceOptionSelectsTheTangentialNetwork) {
  const auto contacts = kFrames / "frame_0008_contacts.csv", particles = kFrames / "frame_0008_particles.csv";
  const ProcessResult tangential =
      analyze({"diagram", "--contacts", contacts.string(), "--particles", particles.string(), "--force", "tangential"});
  const Frame frame = read_frame_csv(contacts, particles);
  expect_same_as_library(tangential, frame, ForceKind::tangential);
  const ProcessResult normal =
      analyze({"diagram", "--contacts", contacts.string(), "--particles", particles.string(), "--force", "normal"});
  expect_same_as_library(normal, frame, ForceKind::normal);
  EXPECT_NE(tangential.out, normal.out) << "the option must change the network";
}

TEST_F(DiagramCli, WithoutParticlesTheVertexCountIsTheLargestIndexPlusOne) {
  const auto contacts = write("c.csv", "i,j,fn,ft\n0,5,1.0,0.5\n7,2,2.0,0.25\n");
  const ProcessResult r = analyze({"diagram", "--contacts", contacts.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto printed = nlohmann::json::parse(r.out);
  EXPECT_EQ(printed.at("vertices"), 8);
  EXPECT_EQ(printed.at("edges"), 2);
  // Particles 1, 3, 4, 6 have no contact: rattlers (0, -1) next to the two contacts' components.
  EXPECT_EQ(printed.at("pd0").size(), 6u);

  // A LAMMPS frame whose largest index is below the particle count: the counts differ with and without the table.
  const auto lammps = kFrames / "frame_0000_contacts.csv";
  const auto listed = read_contacts_csv(lammps);
  std::int64_t largest = -1;
  for (const Contact& c : listed) largest = std::max({largest, c.i, c.j});
  ASSERT_LT(largest + 1, 2000) << "pick a frame where the table adds particles";
  const ProcessResult without = analyze({"diagram", "--contacts", lammps.string()});
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_EQ(nlohmann::json::parse(without.out).at("vertices"), largest + 1);
  expect_same_as_library(without, read_frame_csv(lammps, std::nullopt), ForceKind::normal);
}

// --format gudhi: the library's diagrams in sublevel form, PD0's lines then PD1's, under both conventions.
TEST_F(DiagramCli, GudhiFormatIsTheLibrarysDiagramsNegated) {
  const auto contacts = kFrames / "frame_0009_contacts.csv", particles = kFrames / "frame_0009_particles.csv";
  const FrameDiagrams expected =
      compute_persistence(build_network(read_frame_csv(contacts, particles), ForceKind::normal));
  for (const std::string essential : {"inf", "floor"}) {
    const ProcessResult r = analyze({"diagram", "--contacts", contacts.string(), "--particles", particles.string(),
                                     "--format", "gudhi", "--essential", essential});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, diagram_gudhi_text(expected, parse_gudhi_essential(essential)));
    EXPECT_EQ(r.out.rfind("# ", 0), 0u) << "a comment line first";
    EXPECT_NE(r.out.find("\n1 -"), std::string::npos) << "PD1 lines";
  }
  const ProcessResult by_default =
      analyze({"diagram", "--contacts", contacts.string(), "--particles", particles.string(), "--format", "gudhi"});
  EXPECT_EQ(by_default.out, diagram_gudhi_text(expected, GudhiEssential::inf));
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--format", "csv"}), HasSubstr("csv"));
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--format", "gudhi", "--essential", "x"}),
              HasSubstr("--essential"));
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--essential", "floor"}),
              HasSubstr("--format gudhi"));
}

// Contacts given as force vectors (i,j,fx,fy) go through the same front end as magnitudes.
TEST_F(DiagramCli, ForceVectorsGiveTheDiagramsOfTheirMagnitudes) {
  const auto particles = write("p.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n2,2,0,0.5\n3,1,1,0.5\n");
  // Forces on i: (1,0) pushes 1 away from 0 with 2 and shears by 0; (1,2) by 1 and 0.5; (3,1) by 3 and 1.
  const auto vectors = write("v.csv", "i,j,fx,fy\n1,0,2,0\n1,2,-1,0.5\n3,1,1,3\n");
  const auto magnitudes = write("m.csv", "i,j,fn,ft\n1,0,2,0\n1,2,1,0.5\n3,1,3,1\n");
  for (const std::string force : {"normal", "tangential"}) {
    const ProcessResult from_vectors =
        analyze({"diagram", "--contacts", vectors.string(), "--particles", particles.string(), "--force", force});
    const ProcessResult from_magnitudes =
        analyze({"diagram", "--contacts", magnitudes.string(), "--particles", particles.string(), "--force", force});
    ASSERT_EQ(from_vectors.exit_code, 0) << from_vectors.err;
    EXPECT_EQ(from_vectors.out, from_magnitudes.out) << force;
  }
  EXPECT_THAT(failure_message({"diagram", "--contacts", vectors.string()}),
              AllOf(HasSubstr(vectors.string()), HasSubstr("particles")));
}

TEST_F(DiagramCli, HelpExitsZeroAndMentionsEveryOption) {
  const ProcessResult r = analyze({"diagram", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, AllOf(HasSubstr("--contacts"), HasSubstr("--particles"), HasSubstr("--force"), HasSubstr("--help"),
                           HasSubstr("normal"), HasSubstr("tangential")));
  const ProcessResult top = analyze({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_THAT(top.out, HasSubstr("diagram"));
}

TEST_F(DiagramCli, MissingContactsFileIsNamed) {
  const std::string missing = (std::filesystem::path(FNET_TEST_DATA) / "no_such_frame_contacts.csv").string();
  EXPECT_THAT(failure_message({"diagram", "--contacts", missing}), HasSubstr(missing));
}

TEST_F(DiagramCli, MissingParticlesFileIsNamed) {
  const auto contacts = write("c.csv", "i,j,fn,ft\n0,1,1,1\n");
  const std::string missing = (contacts.parent_path() / "absent_particles.csv").string();
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--particles", missing}),
              HasSubstr(missing));
}

TEST_F(DiagramCli, MissingContactsOptionIsAnError) { EXPECT_THAT(failure_message({"diagram"}), HasSubstr("contacts")); }

TEST_F(DiagramCli, BadForceNameIsNamed) {
  const auto contacts = write("c.csv", "i,j,fn,ft\n0,1,1,1\n");
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--force", "sideways"}),
              HasSubstr("sideways"));
}

TEST_F(DiagramCli, NaNForceIsRejectedNamingFrameAndContact) {
  const auto contacts = write("nan_contacts.csv", "i,j,fn,ft\n0,1,1,1\n1,2,nan,1\n");
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string()}),
              AllOf(HasSubstr(contacts.string()), HasSubstr("contact 1"), HasSubstr("non-finite")));
}

TEST_F(DiagramCli, DuplicateContactIsRejectedNamingBothRows) {
  const auto contacts = write("dup_contacts.csv", "i,j,fn,ft\n0,1,1,1\n1,2,2,1\n1,0,3,1\n");
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string()}),
              AllOf(HasSubstr(contacts.string()), HasSubstr("contact 2"), HasSubstr("duplicate of contact 0")));
}

TEST_F(DiagramCli, MalformedCsvIsRejectedNamingFileAndLine) {
  const auto contacts = write("bad.csv", "i,j,fn,ft\n0,1,1,1\n1,2,two,1\n");
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string()}),
              AllOf(HasSubstr(contacts.string() + ":3"), HasSubstr("'two'")));
}

TEST_F(DiagramCli, IndexBeyondParticleTableIsRejected) {
  const auto contacts = write("c.csv", "i,j,fn,ft\n0,1,1,1\n1,3,1,1\n");
  const auto particles = write("p.csv", "id,x,y,r\n0,0,0,0.5\n1,1,0,0.5\n2,2,0,0.5\n");
  EXPECT_THAT(failure_message({"diagram", "--contacts", contacts.string(), "--particles", particles.string()}),
              AllOf(HasSubstr("contact 1"), HasSubstr("out of range")));
}

}  // namespace
}  // namespace fnet::testing
