#include "common/codec/run_info_json.hpp"

#include <type_traits>

namespace fnet {

nlohmann::json to_json(const RunInfo& info, JsonText text) {
  nlohmann::json out = nlohmann::json::object();
  for_each_run_info_field(
      [&](const RunInfoField& field, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>) {
          if (field.json_text) {
            if (text == JsonText::verbatim) {
              out[field.name] = value;
            } else {  // text that does not parse, or nests deeper than any config, is served as it is, a string
              try {
                out[field.key] = parse_bounded_json(value, kAnnouncementJsonLimits, field.key);
              } catch (const JsonInputError&) {
                out[field.key] = value;
              }
            }
            return;
          }
        }
        out[field.key] = value;
      },
      info);
  return out;
}

RunInfo run_info_from_json(const nlohmann::json& v) {
  RunInfo info;
  for_each_run_info_field(
      [&](const RunInfoField& field, auto& value) {
        using T = std::decay_t<decltype(value)>;
        if (field.since_v2 && !v.contains(field.key)) return;  // written before version 2
        if constexpr (std::is_same_v<T, std::string>) {
          if (field.json_text) {
            if (v.contains(field.name)) {
              value = v.at(field.name).get<std::string>();
            } else {
              const nlohmann::json& parsed = v.at(field.key);
              value = parsed.is_string() ? parsed.get<std::string>() : parsed.dump();
            }
            return;
          }
        }
        value = v.at(field.key).get<T>();
      },
      info);
  return info;
}

}  // namespace fnet
