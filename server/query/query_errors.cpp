#include "server/query/query_errors.hpp"

#include <utility>

namespace fnet::query {

UnknownRun::UnknownRun(std::string run_id)
    : std::runtime_error("unknown run '" + run_id + "'"), run(std::move(run_id)) {}

UnknownFrame::UnknownFrame(std::string run_id, std::uint32_t index)
    : std::runtime_error("run '" + run_id + "' has no analyzed frame " + std::to_string(index)),
      run(std::move(run_id)),
      frame(index) {}

NoNetwork::NoNetwork(std::string run_id, std::uint32_t index, const std::string& why)
    : std::runtime_error(why), run(std::move(run_id)), frame(index), reason(why) {}

}  // namespace fnet::query
