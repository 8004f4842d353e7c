// A blocking JSON-RPC client for fnet-server: one TCP connection, one request at a time, and
// notifications read off the same connection (for watch).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>  // Boost 1.74's asio needs it first under C++20

#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>
#include <nlohmann/json.hpp>

namespace fnet::client {

using json = nlohmann::json;

// The server could not be reached or the connection broke.
class ConnectionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The server answered with a JSON-RPC error.
class CallError : public std::runtime_error {
 public:
  CallError(int code, const std::string& message, json data)
      : std::runtime_error(message), code_(code), data_(std::move(data)) {}
  int code() const { return code_; }
  const json& data() const { return data_; }

 private:
  int code_;
  json data_;
};

// TLS to a server given --tls-cert: its certificate must verify against `ca_file` (PEM), or the
// system's trusted authorities when it is empty, and name the host connected to.
struct TlsOptions {
  bool enabled = false;
  std::string ca_file;
};

class RpcClient {
 public:
  // With a `token`, the connection presents it first (the auth request of proto/api.md, "Access"):
  // a server that asks for one runs no method before it; a wrong one is a CallError (-32007). A
  // failed TLS handshake (a certificate that does not verify, say) is a ConnectionError.
  RpcClient(const std::string& host, unsigned short port, std::chrono::milliseconds timeout = std::chrono::seconds(30),
            const std::string& token = "", const TlsOptions& tls = {});

  // Sends a request and returns its result; notifications that arrive first are kept for next_notification().
  json call(const std::string& method, const json& params = json::object());
  // Waits up to `timeout` for a notification; nullopt on timeout.
  std::optional<json> next_notification(std::chrono::milliseconds timeout);

 private:
  std::optional<json> read_message(std::chrono::milliseconds timeout);
  void start_tls(const std::string& host, const TlsOptions& tls);
  // Runs the io_context until `result` is set or `timeout` passes (then cancels: operation_aborted).
  void run_until_done(const boost::system::error_code& result, std::chrono::milliseconds timeout);

  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  std::unique_ptr<boost::asio::ssl::context> tls_context_;
  std::unique_ptr<boost::asio::ssl::stream<boost::asio::ip::tcp::socket&>> tls_;  // over socket_, when TLS
  boost::asio::streambuf input_;
  std::chrono::milliseconds timeout_;
  std::int64_t next_id_ = 1;
  std::vector<json> pending_notifications_;
};

}  // namespace fnet::client
