// A query run for a JSON-RPC method: its errors (server/query/query_errors.hpp) become the errors
// proto/api.md names, with the same codes, messages and data.
#pragma once

#include "server/api/api_params.hpp"
#include "server/query/query_errors.hpp"

namespace fnet::server {

// What answer() returns, or the rpc::Error of the query error it threw.
template <class Answer>
auto served(Answer&& answer) -> decltype(answer()) {
  try {
    return answer();
  } catch (const query::UnknownRun& e) {
    unknown_run(e.run);
  } catch (const query::UnknownFrame& e) {
    unknown_frame(e.run, e.frame);
  } catch (const query::NoNetwork& e) {
    no_network(e.run, e.frame, e.reason);
  }
}

}  // namespace fnet::server
