// JSON-RPC 2.0 messages: error codes (standard and fnet's own), responses, notifications.
// The codes are the contract of proto/api.md.
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace fnet::rpc {

using json = nlohmann::json;

enum Code : int {
  kParseError = -32700,
  kInvalidRequest = -32600,
  kMethodNotFound = -32601,
  kInvalidParams = -32602,  // data.parameter: the parameter at fault, when there is one
  kInternalError = -32603,
  // fnet's application codes
  kUnknownRun = -32001,    // data.run: the run named (null when none was and none exists)
  kUnknownFrame = -32002,  // data.run, data.frame
  kTooManySubscriptions = -32003,
  kServerBusy = -32004,
  kNoNetwork = -32005,        // data.run, data.frame, data.reason: the frame's force network is not stored
  kUnknownEnsemble = -32006,  // data.ensemble: the ensemble named, which no announced run belongs to
  kUnauthorized = -32007,     // the server asks for a token and the connection did not present it
  kLimitExceeded = -32008,    // data.limit: the bound passed (proto/api.md's Limits), data.value its value
};

// Thrown by method handlers; becomes an error response with this code, message and data.
class Error : public std::runtime_error {
 public:
  Error(int code, const std::string& message, json data = nullptr)
      : std::runtime_error(message), code_(code), data_(std::move(data)) {}
  int code() const { return code_; }
  const json& data() const { return data_; }

 private:
  int code_;
  json data_;
};

inline json response(const json& id, json result) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}};
}

inline json error_response(const json& id, int code, const std::string& message, const json& data = nullptr) {
  json error = {{"code", code}, {"message", message}};
  if (!data.is_null()) error["data"] = data;
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", std::move(error)}};
}

inline json notification(const std::string& method, json params) {
  return {{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
}

}  // namespace fnet::rpc
