#include "client/fnetctl/csv_provenance.hpp"

#include "common/build_info/build_info.hpp"

namespace fnet::client {

std::string csv_provenance_line(RpcClient& rpc, const std::string& what, const std::string& convention) {
  const json status = rpc.call("server.status");
  const json build = status.value("build", json::object());
  const std::string server = "fnet-server " + build.value("version", std::string("unknown")) + " (commit " +
                             build.value("commit", std::string("unknown")) + ")";
  return "# " + server + ", " + version_line("fnetctl") + "; " + what + "; convention " + convention + "; written " +
         utc_timestamp();
}

}  // namespace fnet::client
