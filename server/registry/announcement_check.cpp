#include "server/registry/announcement_check.hpp"

#include <cmath>
#include <exception>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "common/run/run_names.hpp"

namespace fnet::server {
namespace {

// Reads JSON without building it, stopping at the first value nested deeper than the bound; the
// reason of the first failure is kept.
class DepthBoundedSax : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::string problem;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return enter(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return leave(); }
  bool start_array(std::size_t) override { return enter(); }
  bool end_array() override { return leave(); }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::json::exception& e) override {
    problem = "is not JSON (at byte " + std::to_string(position) + ": " + e.what() + ")";
    return false;
  }

 private:
  bool enter() {
    if (++depth_ <= kMaxConfigDepth) return true;
    problem = "is nested deeper than " + std::to_string(kMaxConfigDepth) + " levels";
    return false;
  }
  bool leave() {
    --depth_;
    return true;
  }
  std::size_t depth_ = 0;
};

std::string config_problem(const std::string& text) {
  if (text.empty()) return {};
  if (text.size() > kMaxConfigBytes)
    return "is " + std::to_string(text.size()) + " bytes, above " + std::to_string(kMaxConfigBytes);
  DepthBoundedSax sax;
  try {
    if (nlohmann::json::sax_parse(text, &sax)) return {};
  } catch (const std::exception& e) {
    return std::string("is not JSON (") + e.what() + ")";
  }
  return sax.problem.empty() ? "is not JSON" : sax.problem;
}

}  // namespace

std::string announcement_problem(const RunInfo& info) {
  if (std::string problem = run_id_problem(info.run_id); !problem.empty()) return problem;
  const std::string run = "run " + info.run_id + ": ";
  if (!info.ensemble.empty())
    if (std::string problem = name_problem(info.ensemble, "ensemble"); !problem.empty()) return run + problem;
  std::string problem;
  for_each_run_info_field(
      [&](const RunInfoField& field, const auto& value) {
        if constexpr (std::is_floating_point_v<std::decay_t<decltype(value)>>) {
          if (problem.empty() && !std::isfinite(value))
            problem = run + field.key + " = " + std::to_string(value) + " is not a finite number";
        }
      },
      info);
  if (!problem.empty()) return problem;
  if (std::string config = config_problem(info.config_json); !config.empty()) return run + "config_json " + config;
  return {};
}

}  // namespace fnet::server
