// The diagram document, the one JSON format of a frame's diagrams: what fnet-analyze diagram and
// fnetctl diagram write reads back exactly, keys describing the source are ignored, and a
// document without the diagram asked for is refused naming its key.
#include "common/codec/diagram_json.hpp"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/diagram_match.hpp"

namespace fnet {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const JsonInputError& e) {  // not JSON, a number outside a double's range, a limit
    return e.what();
  }
  return "<accepted>";
}

// Points with doubles of every kind: random bit patterns (subnormals, huge, tiny), negative zero,
// the never-dying sentinel, values of everyday size. Births >= deaths, as readers require.
FrameDiagrams random_diagrams(std::uint64_t seed, std::size_t n) {
  std::mt19937_64 rng(seed);
  const auto any_double = [&] {
    double v;
    do v = std::bit_cast<double>(rng());
    while (!std::isfinite(v));
    return v;
  };
  std::uniform_real_distribution<double> everyday(0.0, 30.0);
  const std::vector<double> special{
      0.0, -0.0, std::numeric_limits<double>::denorm_min(), DBL_MIN, DBL_MAX, -DBL_MAX, 1e-300, 1e300, 100000.0};
  FrameDiagrams d;
  for (Diagram* diagram : {&d.pd0, &d.pd1}) {
    for (std::size_t k = 0; k < n; ++k) {
      double a = k % 3 == 0 ? any_double() : everyday(rng), b = k % 5 == 0 ? any_double() : everyday(rng);
      if (k < special.size()) a = special[k], b = special[special.size() - 1 - k];
      if (a < b) std::swap(a, b);
      diagram->push_back({a, k % 7 == 0 ? kNeverDies : b});
    }
  }
  d.pd0.push_back({-0.0, -0.0});
  d.vertices = 4000000000u;
  d.edges = 123;
  d.triangles = 0;
  return d;
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

// The text writer is to_json(d).dump() without the DOM: the same document, every number bit for
// bit, and the text reader gives back exactly what was written.
TEST(DiagramJson, DocumentTextRoundTripsEveryDoubleBitForBit) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const FrameDiagrams d = random_diagrams(seed, 3000);
    const std::string text = diagram_document_text(d);
    const nlohmann::json parsed = nlohmann::json::parse(text);
    EXPECT_EQ(parsed, to_json(d));
    for (int dim : {0, 1}) {
      const Diagram& expected = dim == 0 ? d.pd0 : d.pd1;
      EXPECT_TRUE(fnet::testing::bit_identical(document_diagram(parsed, dim), expected))
          << "nlohmann reads it back, dim " << dim;
      EXPECT_TRUE(fnet::testing::bit_identical(parse_document_diagram(text, dim), expected))
          << "the text reader, dim " << dim;
      EXPECT_TRUE(fnet::testing::bit_identical(parse_document_diagram(to_json(d).dump(), dim), expected))
          << "from dump(), dim " << dim;
    }
  }
  FrameDiagrams empty;
  EXPECT_EQ(diagram_document_text(empty), to_json(empty).dump());
  EXPECT_TRUE(parse_document_diagram(diagram_document_text(empty), 1).empty());
}

// Documents other writers may produce: spacing, integers, exponents, escaped or non-ASCII
// strings, nested source keys, a key given twice. Read as nlohmann reads them.
TEST(DiagramJson, TextReaderReadsAnyDocumentAsNlohmannDoes) {
  for (const std::string text : {
           R"({"pd1": [[2, 1], [1.5E0, -1], [3e-1, -0]], "pd0": []})",
           " {\n\t\"pd0\" : [ ] ,\r\n \"pd1\" : [ [ 2.0 , 1.0 ] ] } \n",
           R"({"run": "r\"1\u00e9", "pd1": [[2.5, 0.5]], "frame": {"n": [1, {"x": null}], "ok": true}})",
           "{\"label\": \"gr\xc3\xa4in\", \"pd1\": [[1, 0]]}",
           R"({"p\u0064\u0031": [[4, 3]]})",
           R"({"pd1": [[9, 8]], "pd1": [[7, 6]]})",
           R"({"pd1": [[12345678901234567890, 1], [-0, -0.0]], "z": -1.5e-300})",
       }) {
    const Diagram expected = document_diagram(nlohmann::json::parse(text), 1);
    EXPECT_TRUE(fnet::testing::bit_identical(parse_document_diagram(text, 1), expected)) << text;
  }
}

// Every broken document is refused as nlohmann refuses it, naming the place: the line and column of
// a syntax error, the key and point of a bad diagram.
TEST(DiagramJson, TextReaderRefusesBrokenDocumentsNamingThePlace) {
  const std::string good = R"({"pd0":[[1.0,0.5]],"pd1":[[2.0,1.5],[3.0,-1.0]],"vertices":3})";
  ASSERT_EQ(parse_document_diagram(good, 1).size(), 2u);
  for (std::size_t cut = 0; cut < good.size(); ++cut)  // truncated anywhere
    EXPECT_THAT(error_of([&] { parse_document_diagram(good.substr(0, cut), 1); }),
                AllOf(HasSubstr("not JSON: parse error"), HasSubstr("line 1, column")))
        << good.substr(0, cut);
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2.0,1.5],[3.0,1.]]})", 1); }), HasSubstr("column 26"));
  EXPECT_THAT(error_of([] { parse_document_diagram("{\"pd1\":[[2.0,1.5],\n[nan,1]]}", 1); }),
              HasSubstr("line 2, column 3"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[01,0]]})", 1); }), HasSubstr("column 11"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[1e400,0]]})", 1); }), HasSubstr("1e400"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1]]} x)", 1); }), HasSubstr("column 17"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1]],})", 1); }), HasSubstr("column 16"));
  // Keys the reader does not need are checked all the same.
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1]],"ok":tru})", 1); }), HasSubstr("column 24"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"ok":t,"pd1":[[2,1]]})", 1); }), HasSubstr("column 8"));
  EXPECT_THAT(error_of([] { parse_document_diagram("{\"label\":\"gr\xff\",\"pd1\":[[2,1]]}", 1); }),
              AllOf(HasSubstr("not JSON: parse error"), HasSubstr("UTF-8")));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd0":[[2,1]]})", 1); }), HasSubstr("no \"pd1\""));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"([[2,1]])", 1); }), HasSubstr("no \"pd1\""));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1],[3]]})", 1); }),
              AllOf(HasSubstr("pd1: point 1"), HasSubstr("[3]")));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1],[3,1,0]]})", 1); }), HasSubstr("pd1: point 1"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1],["3",1]]})", 1); }), HasSubstr("pd1: point 1"));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":[[2,1],[1,3]]})", 1); }),
              AllOf(HasSubstr("pd1: point 1"), HasSubstr("birth 1 < death 3")));
  EXPECT_THAT(error_of([] { parse_document_diagram(R"({"pd1":{"a":1}})", 1); }), HasSubstr("pd1: a diagram must be"));
}

// Read through the DOM, a document nested 300 000 deep in a point, or beside the diagrams, is
// refused while it is read: no reader or message recurses into it.
TEST(DiagramJson, DeepNestingIsRefusedNotAStackOverflow) {
  const std::string deep = std::string(300'000, '[') + std::string(300'000, ']');
  EXPECT_THAT(error_of([&] { parse_document_diagram(R"({"pd1":[)" + deep + "]}", 1, "a.json"); }),
              AllOf(HasSubstr("a.json: "), HasSubstr("nested deeper than 64")));
  EXPECT_THAT(error_of([&] { parse_document_diagram(R"({"pd1":[[2,1]],"run":)" + deep + "}", 1, "a.json"); }),
              HasSubstr("nested deeper than 64"));
  EXPECT_THAT(error_of([&] { parse_document_diagram(R"({"pd1":[[1e999,1]]})", 1, "a.json"); }),
              AllOf(HasSubstr("a.json: "), HasSubstr("1e999")));
}

}  // namespace
}  // namespace fnet
