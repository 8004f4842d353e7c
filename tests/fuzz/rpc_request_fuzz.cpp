// A JSON-RPC message as fnet-server reads it from a client: parse_bounded_json within the
// connection's limits, then every method of the API (make_api) over a registry holding a real
// stored run, its heavy work run at once. Whatever the bytes: no crash, no hang, no exception
// but rpc::Error from a method, and every answer serializes. Input: one message.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>

#include "common/codec/bounded_json.hpp"
#include "server/rpc/server_limits.hpp"
#include "tests/fuzz/api_over_store.hpp"

namespace {

// The client as the methods see it: what they send is serialized, never held.
class FuzzPeer final : public fnet::rpc::Peer {
 public:
  bool send(const nlohmann::json& message) override {
    (void)message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return true;
  }
  std::uint64_t id() const override { return 1; }
  void on_close(std::function<void()>) override {}
  bool wait_for_room(std::function<void()>) override { return true; }
  void subscriptions_changed(int) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fnet::fuzz::ApiOverStore api;
  static const auto peer = std::make_shared<FuzzPeer>();
  const fnet::rpc::ServerLimits limits;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  nlohmann::json message;
  try {
    message = fnet::parse_bounded_json(text, fnet::JsonLimits{size, limits.max_json_depth}, "the request");
  } catch (const fnet::JsonInputError&) {
    return 0;
  }
  const auto call = [&](const nlohmann::json& request) {
    if (!request.is_object() || !request.contains("method") || !request["method"].is_string()) return;
    const nlohmann::json params = request.value("params", nlohmann::json::object());
    if (!params.is_object() && !params.is_array()) return;
    try {
      api.handler(request["method"].get<std::string>(), params, peer, [](nlohmann::json result, std::exception_ptr e) {
        (void)result.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        if (!e) return;
        try {
          std::rethrow_exception(e);
        } catch (const fnet::rpc::Error&) {
        } catch (const std::exception& other) {
          std::cerr << "a method ended with " << other.what() << " instead of an rpc::Error\n";
          std::abort();
        }
      });
    } catch (const fnet::rpc::Error&) {
    }
  };
  if (message.is_array() && message.size() <= limits.max_batch_calls)
    for (const nlohmann::json& request : message) call(request);
  else
    call(message);
  return 0;
}
