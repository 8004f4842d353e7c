// One JSON-RPC connection to fnet-server read line by line, as a document writes the exchanges:
// each reply matched to its request, the notifications that come first kept in order.
#pragma once

#include <poll.h>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/asio.hpp>
#include <nlohmann/json.hpp>

namespace fnet::e2e {

// Whole lines: requests as a document writes them, every reply and notification.
class LineConnection {
 public:
  explicit LineConnection(unsigned short port) : socket_(io_) {
    socket_.connect({boost::asio::ip::make_address("127.0.0.1"), port});
  }
  void send(const std::string& line) { boost::asio::write(socket_, boost::asio::buffer(line + "\n")); }
  std::optional<nlohmann::json> next(std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
      if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
        const std::string line = buffer_.substr(0, nl);
        buffer_.erase(0, nl + 1);
        return nlohmann::json::parse(line);
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return std::nullopt;
      pollfd p{socket_.native_handle(), POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
      char chunk[65536];
      boost::system::error_code ec;
      const std::size_t n = socket_.read_some(boost::asio::buffer(chunk), ec);
      if (ec) return std::nullopt;
      buffer_.append(chunk, n);
    }
  }
  // The response to request `id`; notifications that come first are kept in `notifications`.
  nlohmann::json reply(const nlohmann::json& id) {
    while (const auto m = next()) {
      if (m->contains("id") && (*m)["id"] == id) return *m;
      notifications.push_back(*m);
    }
    throw std::runtime_error("no reply to request " + id.dump());
  }
  nlohmann::json call(const std::string& method, const nlohmann::json& params) {
    const nlohmann::json id = next_id_++;
    send(nlohmann::json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}}.dump());
    return reply(id);
  }
  std::vector<nlohmann::json> notifications;

 private:
  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  std::string buffer_;
  int next_id_ = 1000;
};

}  // namespace fnet::e2e
