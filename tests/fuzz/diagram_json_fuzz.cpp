// A diagram document as fnet-analyze distance reads it: parse_document_diagram, whose one-pass
// reader of plain documents must agree bit for bit with the DOM it falls back to (both read the
// same diagram, or both refuse), and whose every error is JsonInputError naming the document or
// std::invalid_argument naming the key. Input: the document.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "common/codec/diagram_json.hpp"
#include "tests/fuzz/fuzz_input.hpp"
#include "tests/support/diagram_match.hpp"

namespace {

constexpr const char* kSource = "doc.json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = fnet::fuzz;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const int dim : {0, 1}) {
    std::optional<fnet::Diagram> read, dom;
    try {
      read = fnet::parse_document_diagram(text, dim, kSource);
    } catch (const fnet::JsonInputError& e) {
      fuzz::require_names(e, {kSource});
    } catch (const std::invalid_argument& e) {
      fuzz::require_names(e, {fnet::diagram_key(dim)});
    }
    try {
      dom = fnet::document_diagram(fnet::parse_bounded_json(text, fnet::kDiagramDocumentLimits, kSource), dim);
    } catch (const fnet::JsonInputError&) {
    } catch (const std::invalid_argument&) {
    }
    if (read.has_value() != dom.has_value() || (read && !fnet::testing::bit_identical(*read, *dom))) {
      std::cerr << "fuzz: the one-pass reader and the DOM disagree on " << fnet::diagram_key(dim) << "\n";
      std::abort();
    }
  }
  return 0;
}
