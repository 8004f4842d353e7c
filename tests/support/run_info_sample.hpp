// A RunInfo whose every field holds a value of its own, and the field-by-field comparison, for the
// round trips of each codec: a codec that drops or swaps a field cannot carry the sample unchanged.
#pragma once

#include <limits>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "common/run/run_frame.hpp"

namespace fnet::testing {

// Built from the field list, so a field added to RunInfo gets a value too. Integers use their top
// bit and doubles are no floats, so a narrower type on the way shows; config_json is JSON in its
// canonical form (sorted keys, no spaces), which the parsed JSON form reproduces.
inline RunInfo distinct_run_info() {
  RunInfo info;
  int k = 0;
  for_each_run_info_field(
      [&k](const RunInfoField& field, auto& value) {
        ++k;
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::string>) {
          value = field.json_text ? R"({"field":")" + std::string(field.name) + R"(","k":)" + std::to_string(k) + "}"
                                  : std::string(field.name) + "-" + std::to_string(k);
        } else if constexpr (std::is_floating_point_v<T>) {
          value = k + 1.0 / 3;
        } else {
          value = static_cast<T>(std::numeric_limits<T>::max() / 2 + 1 + static_cast<T>(k));
        }
      },
      info);
  return info;
}

inline void expect_same_fields(const RunInfo& want, const RunInfo& got) {
  for_each_run_info_field(
      [](const RunInfoField& field, const auto& w, const auto& g) { EXPECT_EQ(w, g) << "field " << field.name; }, want,
      got);
  EXPECT_EQ(want, got);  // every member, whether listed or not
}

}  // namespace fnet::testing
