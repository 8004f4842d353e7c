// JSON codecs for diagrams, and the diagram document: one format for every tool. fnet-analyze
// diagram and fnetctl diagram --format json write it, fnet-analyze distance reads it:
//   {"pd0": [[birth, death], ...], "pd1": [...], "vertices": N, "edges": E, "triangles": T}
// A writer may add where the diagrams came from ("run", "frame", "force", "rho", "z"); readers
// ignore keys they do not need.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/codec/bounded_json.hpp"
#include "common/topology/diagram.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {

nlohmann::json to_json(const Diagram& diagram);         // [[birth, death], ...]
nlohmann::json to_json(const FrameDiagrams& diagrams);  // the diagram document

// The diagram document as text, the same as to_json(diagrams).dump() reads (keys, order, numbers
// bit for bit), written straight into one buffer: no DOM, a few bytes of work per number.
std::string diagram_document_text(const FrameDiagrams& diagrams);

// Throws std::invalid_argument naming what is wrong (not an array of pairs, non-finite, birth < death).
Diagram diagram_from_json(const nlohmann::json& value);

// "pd0" or "pd1": the key of the diagram of dimension dim (0 or 1) in a document.
std::string diagram_key(int dim);

// The diagram of dimension dim of a document. Throws std::invalid_argument naming the key when
// the document is not an object, lacks it, or holds no valid diagram under it.
Diagram document_diagram(const nlohmann::json& document, int dim);

// Diagram documents may be large (one point takes some 40 bytes); they nest 3 deep, and what
// writers add beside the diagrams little more.
inline constexpr JsonLimits kDiagramDocumentLimits{std::size_t{1} << 30, 64};

// document_diagram of a document given as text, `source` naming it in messages (a file). The shape
// writers produce (an object whose values are plain: numbers, strings without escapes or non-ASCII
// bytes, literals, arrays and objects of those) is read in one pass without a DOM; anything else,
// and every error, goes through parse_bounded_json and document_diagram, so a bad document throws
// what they throw: JsonInputError "SOURCE: not JSON: parse error at line L, column C: ...", or a
// limit of kDiagramDocumentLimits exceeded, or std::invalid_argument naming the key.
Diagram parse_document_diagram(std::string_view text, int dim, const std::string& source = "diagram document");

}  // namespace fnet
