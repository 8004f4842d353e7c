// The methods of fnet-server that serve ensembles of realizations (proto/api.md): ensembles.list,
// ensemble.series, ensemble.subscribe, ensemble.unsubscribe; and series.get's `ratio`, a run's
// d_B / d_Wq frame by frame.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "server/analysis/api_methods.hpp"

namespace fnet::server {

struct EnsembleMethod {
  std::vector<std::string_view> params;  // every parameter the method accepts
  std::function<nlohmann::json(const nlohmann::json& params, const std::shared_ptr<rpc::Session>& session)> run;
};

// The four ensemble methods by name; their subscriptions end with their connection.
std::map<std::string, EnsembleMethod, std::less<>> ensemble_methods(ApiContext& context);

// series.get given `ratio`: the answer of series.get with value[k] = d_B / d_Wq of frame k.
nlohmann::json series_ratio_get(const Registry& registry, const nlohmann::json& params);

}  // namespace fnet::server
