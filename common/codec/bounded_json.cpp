#include "common/codec/bounded_json.hpp"

namespace fnet {
namespace {

// Thrown from the parser's callback: nlohmann's parser holds no state that outlives the call, so
// leaving it by an exception is safe and stops it at once.
struct DepthPassed {};

// The number as nlohmann's message quotes it ("number overflow parsing '1e999'"), cut short.
std::string quoted_number(const std::string& message) {
  const std::size_t open = message.find('\'');
  const std::size_t close = message.rfind('\'');
  if (open == std::string::npos || close <= open) return {};
  std::string number = message.substr(open + 1, close - open - 1);
  if (number.size() > 24) number = number.substr(0, 24) + "...";
  return " (" + number + ")";
}

}  // namespace

nlohmann::json parse_bounded_json(std::string_view text, std::size_t max_depth) {
  std::size_t opened = 0;  // the depth of the container being read
  const nlohmann::json::parser_callback_t bound = [&](int, nlohmann::json::parse_event_t event, nlohmann::json&) {
    using E = nlohmann::json::parse_event_t;
    if (event == E::object_start || event == E::array_start) {
      if (++opened > max_depth) throw DepthPassed{};
    } else if (event == E::object_end || event == E::array_end) {
      --opened;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, bound);
  } catch (const DepthPassed&) {
    throw JsonTextError(JsonTextError::Kind::too_deep, 0,
                        "JSON nested deeper than " + std::to_string(max_depth) + " levels (arrays and objects)");
  } catch (const nlohmann::json::parse_error& e) {
    throw JsonTextError(JsonTextError::Kind::syntax, e.byte, "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::out_of_range& e) {
    // 406: a number whose value no double holds (1e999).
    throw JsonTextError(JsonTextError::Kind::number_range, 0,
                        "a number outside the range of a double" + quoted_number(e.what()));
  } catch (const nlohmann::json::exception&) {
    throw JsonTextError(JsonTextError::Kind::syntax, 0, "not valid JSON");
  }
}

}  // namespace fnet
