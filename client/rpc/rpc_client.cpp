#include "client/rpc/rpc_client.hpp"

#include <istream>

namespace fnet::client {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

RpcClient::RpcClient(const std::string& host, unsigned short port, std::chrono::milliseconds timeout,
                     const std::string& token, const TlsOptions& tls)
    : socket_(io_), timeout_(timeout) {
  boost::system::error_code ec;
  tcp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec) throw ConnectionError("cannot resolve " + host + ": " + ec.message());
  asio::connect(socket_, endpoints, ec);
  if (ec)
    throw ConnectionError("cannot connect to fnet-server at " + host + ":" + std::to_string(port) + ": " +
                          ec.message());
  if (tls.enabled) start_tls(host, tls);
  if (!token.empty()) call("auth", {{"token", token}});
}

void RpcClient::start_tls(const std::string& host, const TlsOptions& tls) {
  namespace ssl = asio::ssl;
  tls_context_ = std::make_unique<ssl::context>(ssl::context::tls_client);
  tls_context_->set_options(ssl::context::no_sslv2 | ssl::context::no_sslv3 | ssl::context::no_tlsv1 |
                            ssl::context::no_tlsv1_1);
  boost::system::error_code ec;
  if (tls.ca_file.empty())
    tls_context_->set_default_verify_paths(ec);
  else
    tls_context_->load_verify_file(tls.ca_file, ec);
  if (ec) throw ConnectionError("cannot use '" + tls.ca_file + "' as PEM certificates to trust: " + ec.message());
  tls_ = std::make_unique<ssl::stream<tcp::socket&>>(socket_, *tls_context_);
  tls_->set_verify_mode(ssl::verify_peer);
  tls_->set_verify_callback(ssl::host_name_verification(host));
  SSL_set_tlsext_host_name(tls_->native_handle(), host.c_str());  // SNI
  boost::system::error_code result = asio::error::would_block;
  tls_->async_handshake(ssl::stream_base::client, [&](boost::system::error_code got) { result = got; });
  run_until_done(result, timeout_);
  if (result == asio::error::operation_aborted) throw ConnectionError("the TLS handshake with " + host + " timed out");
  if (result) throw ConnectionError("TLS handshake with " + host + " failed: " + result.message());
}

void RpcClient::run_until_done(const boost::system::error_code& result, std::chrono::milliseconds timeout) {
  io_.restart();
  io_.run_for(timeout);
  if (result == asio::error::would_block) {  // timed out: cancel and let the handler run
    socket_.cancel();
    io_.restart();
    io_.run();
  }
}

std::optional<json> RpcClient::read_message(std::chrono::milliseconds timeout) {
  boost::system::error_code result = asio::error::would_block;
  std::size_t n = 0;
  const auto done = [&](boost::system::error_code ec, std::size_t got) {
    result = ec;
    n = got;
  };
  if (tls_)
    asio::async_read_until(*tls_, input_, '\n', done);
  else
    asio::async_read_until(socket_, input_, '\n', done);
  run_until_done(result, timeout);
  if (result == asio::error::operation_aborted) return std::nullopt;
  if (result) throw ConnectionError("connection to fnet-server lost: " + result.message());
  std::string line(n, '\0');
  std::istream(&input_).read(line.data(), static_cast<std::streamsize>(n));
  try {
    return json::parse(line);
  } catch (const json::parse_error&) {
    throw ConnectionError("fnet-server sent a line that is not JSON");
  }
}

json RpcClient::call(const std::string& method, const json& params) {
  const std::int64_t id = next_id_++;
  const std::string request =
      json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump() + "\n";
  boost::system::error_code ec;
  if (tls_)
    asio::write(*tls_, asio::buffer(request), ec);
  else
    asio::write(socket_, asio::buffer(request), ec);
  if (ec) throw ConnectionError("cannot send to fnet-server: " + ec.message());
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) throw ConnectionError("fnet-server did not answer '" + method + "' in time");
    std::optional<json> message = read_message(left);
    if (!message) continue;
    if (!message->contains("id")) {  // a notification that raced the response
      pending_notifications_.push_back(std::move(*message));
      continue;
    }
    if ((*message)["id"] != id) continue;
    if (message->contains("error")) {
      const json& e = (*message)["error"];
      throw CallError(e.value("code", 0), e.value("message", std::string("error")), e.value("data", json()));
    }
    return (*message)["result"];
  }
}

std::optional<json> RpcClient::next_notification(std::chrono::milliseconds timeout) {
  if (!pending_notifications_.empty()) {
    json n = std::move(pending_notifications_.front());
    pending_notifications_.erase(pending_notifications_.begin());
    return n;
  }
  while (true) {
    std::optional<json> message = read_message(timeout);
    if (!message) return std::nullopt;
    if (!message->contains("id")) return message;
  }
}

}  // namespace fnet::client
