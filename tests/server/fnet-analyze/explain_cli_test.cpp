// fnet-analyze explain as users run it on frame CSVs: JSON equal to the library's answer, a change
// planted in a file found where it was planted, usage errors exit 2 naming the fault.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/codec/explain_json.hpp"
#include "common/codec/frame_csv.hpp"
#include "tests/server/fnet-analyze/analyze_cli_fixture.hpp"
#include "tests/support/doc_names.hpp"

namespace fnet::testing {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const std::filesystem::path kFrames = std::filesystem::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";

std::string contacts_of(int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%04d_contacts.csv", frame);
  return (kFrames / name).string();
}
std::string particles_of(int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%04d_particles.csv", frame);
  return (kFrames / name).string();
}

class ExplainCli : public AnalyzeCliTest {
 protected:
  nlohmann::json json_of(const std::vector<std::string>& args) {
    const ProcessResult r = analyze(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    try {
      return nlohmann::json::parse(r.out);
    } catch (const nlohmann::json::exception&) {
      ADD_FAILURE() << "not JSON: " << r.out.substr(0, 200);
      return {};
    }
  }
};

TEST_F(ExplainCli, JsonIsTheLibrarysExplanation) {
  const Frame a = read_frame_csv(contacts_of(9), particles_of(9)),
              b = read_frame_csv(contacts_of(10), particles_of(10));
  for (const int dim : {0, 1}) {
    const nlohmann::json printed =
        json_of({"explain", contacts_of(9), contacts_of(10), "--metric", "wasserstein2", "--dim", std::to_string(dim),
                 "--k", "4", "--particles-a", particles_of(9), "--particles-b", particles_of(10), "--format", "json"});
    const nlohmann::json expected =
        explain_json(a, b, {DistanceMetric::wasserstein(2), dim, ForceKind::normal, EssentialConvention::floor, 4});
    EXPECT_EQ(printed.at("value"), expected.at("value"));
    EXPECT_EQ(printed.at("explain"), expected.at("explain"));
    EXPECT_EQ(printed.at("explain").size(), 4u);
    EXPECT_EQ(printed.at("metric"), "wasserstein2");
    EXPECT_EQ(printed.at("q"), 2.0);
    EXPECT_EQ(printed.at("dim"), dim);
    EXPECT_EQ(printed.at("force"), "normal");
    EXPECT_EQ(printed.at("essential"), "floor");
    EXPECT_EQ(printed.at("k"), 4);
    const auto& first = printed.at("explain")[0];
    EXPECT_EQ(first.at("rank"), 1);
    for (const char* side : {"a", "b"}) {
      if (first.at(side).is_null()) continue;
      const auto& birth = first.at(side).at("birth_simplex");
      EXPECT_EQ(birth.at("grains").size(), static_cast<std::size_t>(dim + 1));
      EXPECT_EQ(birth.at("positions").size(), birth.at("grains").size());
    }
  }
}

// Forces of the contacts in the lower-left quarter of frame 10, tripled, written as a CSV.
TEST_F(ExplainCli, APlantedChangeIsExplainedByGrainsOfItsCorner) {
  const Frame a = read_frame_csv(contacts_of(10), particles_of(10));
  double x_lo = std::numeric_limits<double>::infinity(), y_lo = x_lo, x_hi = -x_lo, y_hi = -x_lo;
  for (const Particle& p : a.particles)
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x), y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
  const double x_cut = x_lo + 0.25 * (x_hi - x_lo), y_cut = y_lo + 0.25 * (y_hi - y_lo);
  const auto in_corner = [&](double x, double y) { return x <= x_cut && y <= y_cut; };
  std::ostringstream csv;
  csv.precision(17);
  csv << "i,j,fn,ft\n";
  for (const Contact& c : a.contacts) {
    const Particle &p = a.particles[c.i], &q = a.particles[c.j];
    const double f = in_corner(p.x, p.y) && in_corner(q.x, q.y) ? 3 : 1;
    csv << c.i << "," << c.j << "," << c.fn * f << "," << c.ft * f << "\n";
  }
  const auto changed = write("changed_contacts.csv", csv.str());
  const nlohmann::json printed =
      json_of({"explain", contacts_of(10), changed.string(), "--metric", "bottleneck", "--dim", "1", "--k", "1",
               "--particles-a", particles_of(10), "--particles-b", particles_of(10), "--format", "json"});
  ASSERT_EQ(printed.at("explain").size(), 1u);
  const auto& term = printed.at("explain")[0];
  EXPECT_EQ(term.at("cost"), printed.at("value")) << "the first term attains d_B";
  ASSERT_FALSE(term.at("b").is_null());
  for (const char* simplex : {"birth_simplex", "death_simplex"}) {
    const auto& s = term.at("b").at(simplex);
    if (s.is_null()) continue;
    for (const auto& xy : s.at("positions"))
      EXPECT_TRUE(in_corner(xy[0].get<double>(), xy[1].get<double>())) << simplex << " grain at " << xy.dump();
  }
}

TEST_F(ExplainCli, UnchangedFrameHasNoTermsAndNoPositionsWithoutParticles) {
  const nlohmann::json same =
      json_of({"explain", contacts_of(4), contacts_of(4), "--metric", "bottleneck", "--format", "json"});
  EXPECT_EQ(same.at("value"), 0.0);
  EXPECT_TRUE(same.at("explain").empty());
  const nlohmann::json other =
      json_of({"explain", contacts_of(4), contacts_of(5), "--metric", "bottleneck", "--dim", "0", "--format", "json"});
  ASSERT_FALSE(other.at("explain").empty());
  EXPECT_FALSE(other.at("explain")[0].at("b").at("birth_simplex").contains("positions"));
}

TEST_F(ExplainCli, TableHasOneRowPerTerm) {
  const ProcessResult r = analyze({"explain", contacts_of(9), contacts_of(10), "--metric", "bottleneck", "--k", "3",
                                   "--particles-a", particles_of(9), "--particles-b", particles_of(10)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, AllOf(HasSubstr("bottleneck PD1 normal (floor)"), HasSubstr("rank"), HasSubstr("a grains")));
  std::istringstream lines(r.out);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) rows += line.rfind("   ", 0) == 0;
  EXPECT_EQ(rows, 3);
}

TEST_F(ExplainCli, BadUsageExitsTwoNamingTheFault) {
  const std::string a = contacts_of(4), b = contacts_of(5);
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "bottleneck", "--k", "0"}), HasSubstr("--k"));
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "bottleneck", "--format", "xml"}),
              AllOf(HasSubstr("--format"), HasSubstr("xml")));
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "manhattan"}), HasSubstr("manhattan"));
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "bottleneck", "--dim", "2"}), HasSubstr("--dim"));
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "bottleneck", "--force", "shear"}), HasSubstr("shear"));
  EXPECT_THAT(fails_with(2, {"explain", a, "--metric", "bottleneck"}), HasSubstr("two contacts files"));
  EXPECT_THAT(fails_with(2, {"explain", a, "absent.csv", "--metric", "bottleneck"}),
              AllOf(HasSubstr("absent.csv"), HasSubstr("no such file")));
  EXPECT_THAT(fails_with(2, {"explain", a, b, "--metric", "bottleneck", "--particles-b", "nowhere.csv"}),
              AllOf(HasSubstr("--particles-b"), HasSubstr("no such file")));
}

TEST_F(ExplainCli, InvalidFrameExitsOneNamingTheFile) {
  const auto bad = write("self_contact.csv", "i,j,fn,ft\n0,1,1,1\n2,2,1,1\n");
  EXPECT_THAT(fails_with(1, {"explain", contacts_of(4), bad.string(), "--metric", "bottleneck"}),
              HasSubstr("self_contact.csv"));
}

// proto/api.md's example, run as it is written (paths relative to the repository): the same
// output but for the time taken.
TEST_F(ExplainCli, TheApiDocumentsExampleRuns) {
  const std::filesystem::path source(FNET_SOURCE_DIR);
  const std::string doc = read_text(source / "proto" / "api.md");
  const std::string prompt = "$ fnet-analyze explain ";
  const std::size_t at = doc.find(prompt);
  ASSERT_NE(at, std::string::npos) << "no example of fnet-analyze explain";
  const std::size_t line_end = doc.find('\n', at), out_end = doc.find('\n', line_end + 1);
  std::istringstream words(doc.substr(at + 2, line_end - at - 2));
  std::vector<std::string> args;
  for (std::string w; words >> w;) args.push_back(w.rfind("tests/", 0) == 0 ? (source / w).string() : w);
  ASSERT_EQ(args.at(0), "fnet-analyze");
  args.erase(args.begin());
  nlohmann::json documented = nlohmann::json::parse(doc.substr(line_end + 1, out_end - line_end - 1));
  nlohmann::json printed = json_of(args);
  ASSERT_TRUE(printed.contains("seconds"));
  documented.erase("seconds");
  printed.erase("seconds");
  EXPECT_EQ(printed, documented);
}

}  // namespace
}  // namespace fnet::testing
