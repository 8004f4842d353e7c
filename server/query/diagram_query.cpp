#include "server/query/diagram_query.hpp"

#include "server/query/query_errors.hpp"

namespace fnet::query {

DiagramAnswer diagram_query(const FrameLookup& frames, const DiagramRequest& r) {
  const auto f = frames.frame(r.run, r.frame);
  if (!f) throw UnknownFrame(r.run, r.frame);
  const FrameDiagrams& d = f->diagrams[r.force];
  return {f->header, d.vertices, d.edges, d.triangles, r.dim == 0 ? d.pd0 : d.pd1};
}

}  // namespace fnet::query
