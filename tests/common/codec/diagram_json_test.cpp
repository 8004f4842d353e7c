// The diagram document, the one JSON format of a frame's diagrams: what fnet-analyze diagram and
// fnetctl diagram write reads back exactly, keys describing the source are ignored, and a
// document without the diagram asked for is refused naming its key.
#include "common/codec/diagram_json.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet {
namespace {

using ::testing::HasSubstr;

template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<accepted>";
}

TEST(DiagramJson, DocumentRoundTripsBothDimensionsExactly) {
  FrameDiagrams d;
  d.pd0 = {{0.1 + 0.2, 0.3}, {1.0 / 3.0, kNeverDies}};
  d.pd1 = {{2.000000000000001, 1.5}};
  d.vertices = 5;
  d.edges = 6;
  d.triangles = 1;
  nlohmann::json document = nlohmann::json::parse(to_json(d).dump());
  document["run"] = "r";  // where it came from: ignored by readers
  document["frame"] = 3;
  EXPECT_TRUE(document_diagram(document, 0) == d.pd0);
  EXPECT_TRUE(document_diagram(document, 1) == d.pd1);
  EXPECT_EQ(document["vertices"], 5);
  EXPECT_EQ(diagram_key(1), "pd1");
}

TEST(DiagramJson, MissingOrBadDiagramIsNamedByItsKey) {
  EXPECT_THAT(error_of([] { document_diagram(nlohmann::json::parse(R"({"pd0": []})"), 1); }), HasSubstr("\"pd1\""));
  EXPECT_THAT(error_of([] { document_diagram(nlohmann::json::array(), 0); }), HasSubstr("\"pd0\""));
  EXPECT_THAT(error_of([] { document_diagram(nlohmann::json::parse(R"({"pd1": [[1, 2]]})"), 1); }),
              HasSubstr("pd1: point 0"));
  // A diagram.get answer is not a document: its points have no dimension key.
  EXPECT_THAT(error_of([] { document_diagram(nlohmann::json::parse(R"({"dim": 1, "points": []})"), 1); }),
              HasSubstr("\"pd1\""));
}

}  // namespace
}  // namespace fnet
