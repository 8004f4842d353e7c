#include "server/query/network_query.hpp"

#include "common/topology/force_network.hpp"
#include "server/query/query_errors.hpp"

namespace fnet::query {

NetworkAnswer network_query(const FrameLookup& frames, const NetworkRequest& r) {
  const auto f = frames.row(r.run, r.frame);
  if (!f) throw UnknownFrame(r.run, r.frame);
  NetworkAnswer out;
  out.header = f->header;
  out.network = frames.network(r.run, r.frame);
  out.mean_normal = build_network(out.network, ForceKind::normal).mean_force;
  out.mean_tangential = build_network(out.network, ForceKind::tangential).mean_force;
  if (!out.network.particles.empty()) out.domain = block_domain(out.network);
  return out;
}

}  // namespace fnet::query
