#include "server/api/network_methods.hpp"

#include "server/api/api_params.hpp"
#include "server/api/registry_frames.hpp"
#include "server/api/served_query.hpp"
#include "server/query/network_query.hpp"

namespace fnet::server {

json network_get(const Registry& registry, const json& params) {
  query::NetworkRequest r;
  r.frame = require_index(params, "frame");
  r.run = resolve_run(registry, params);
  const query::NetworkAnswer a = served([&] { return query::network_query(RegistryFrames(registry), r); });
  const Frame& f = a.network;
  json particles = json::array();
  for (const Particle& p : f.particles)
    particles.push_back(f.dimension == 3 ? json::array({p.x, p.y, p.r, p.z}) : json::array({p.x, p.y, p.r}));
  json contacts = json::array();
  for (const Contact& c : f.contacts) contacts.push_back(json::array({c.i, c.j, c.fn, c.ft}));
  json domain = nullptr;
  if (a.domain) {
    const BlockDomain& d = *a.domain;
    domain = f.dimension == 3 ? json::array({d.x_lo, d.x_hi, d.y_lo, d.y_hi, d.z_lo, d.z_hi})
                              : json::array({d.x_lo, d.x_hi, d.y_lo, d.y_hi});
  }
  return {{"run", r.run},
          {"frame", r.frame},
          {"rho", a.header.rho},
          {"z", a.header.z},
          {"dimension", f.dimension},
          {"particle_count", f.particle_count},
          {"particles", particles},
          {"contacts", contacts},
          {"mean_force", {{"normal", a.mean_normal}, {"tangential", a.mean_tangential}}},
          {"domain", domain}};
}

}  // namespace fnet::server
