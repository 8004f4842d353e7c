// The first line of every CSV fnetctl writes: a comment naming where the numbers came from, so
// that a CSV file kept alone still says it. Readers skip it as a comment (`#`): numpy's loadtxt
// and genfromtxt do by default, pandas with comment="#".
#pragma once

#include <string>

#include "client/rpc/rpc_client.hpp"

namespace fnet::client {

// "# fnet-server VERSION (commit C), fnetctl VERSION (commit C); WHAT; convention CONV; written
// 2026-12-03T09:47:32Z" — the server's build from server.status, this program's own, `what` the
// request (run, metric, PD, force), and the time. Ends without a newline.
std::string csv_provenance_line(RpcClient& rpc, const std::string& what, const std::string& convention);

}  // namespace fnet::client
