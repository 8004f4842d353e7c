#include "common/codec/distance_json.hpp"

namespace fnet {

nlohmann::json to_json(const DistanceResult& result) {
  if (result.infinite)
    return {{"value", nullptr}, {"lower", nullptr}, {"upper", nullptr},
            {"exact", true},    {"infinite", true}, {"reason", result.reason}};
  return {{"value", result.value}, {"lower", result.lower}, {"upper", result.upper}, {"exact", result.exact}};
}

}  // namespace fnet
