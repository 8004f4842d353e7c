// The JSON-RPC methods of fnet-server (proto/api.md is their reference).
#pragma once

#include "server/api/method.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::server {

// Every method by name, each with the parameters it declares beside the code that reads them.
MethodTable method_table(ApiContext& context);

rpc::Handler make_api(ApiContext& context);

}  // namespace fnet::server
