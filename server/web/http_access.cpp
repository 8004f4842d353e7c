#include "server/web/http_access.hpp"

#include <optional>

#include <boost/asio/ip/address.hpp>
#include <boost/beast/websocket/rfc6455.hpp>

namespace fnet::web {
namespace http = boost::beast::http;

namespace {

std::string_view view(boost::beast::string_view s) { return {s.data(), s.size()}; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

// The value of `name` in a list of `name=value` pairs separated by `separator`.
std::optional<std::string_view> pair_value(std::string_view pairs, std::string_view name, char separator) {
  while (!pairs.empty()) {
    const std::size_t end = pairs.find(separator);
    const std::string_view pair = trim(pairs.substr(0, end));
    const std::size_t eq = pair.find('=');
    if (eq != std::string_view::npos && pair.substr(0, eq) == name) return pair.substr(eq + 1);
    if (end == std::string_view::npos) break;
    pairs.remove_prefix(end + 1);
  }
  return std::nullopt;
}

// The host of a Host header ("127.0.0.1:8080", "[::1]:8080", "localhost").
std::string_view host_name(std::string_view host) {
  if (!host.empty() && host.front() == '[') return host.substr(1, host.find(']') - 1);
  return host.substr(0, host.find(':'));
}

bool loopback_name(std::string_view host) {
  const std::string_view name = host_name(host);
  return name == "localhost" || rpc::is_loopback(std::string(name));
}

Admission refusal(http::status status, std::string message) {
  return {Admission::Verdict::refuse, status, std::move(message), {}, {}};
}

}  // namespace

std::string token_cookie_name(unsigned short port) { return "fnet_token_" + std::to_string(port); }

Admission admit(const http::request<http::string_body>& request, const rpc::Access& access, unsigned short port) {
  const std::string_view target = view(request.target());
  const std::string_view path = target.substr(0, target.find('?'));
  const std::string_view host = view(request[http::field::host]);
  const bool upgrade = boost::beast::websocket::is_upgrade(request);
  if (upgrade && request.count(http::field::origin)) {
    const std::string_view origin = view(request[http::field::origin]);
    const std::size_t scheme = origin.find("://");
    if (scheme == std::string_view::npos || origin.substr(scheme + 3) != host)
      return refusal(http::status::forbidden, "a WebSocket of this server opens from its own pages only (origin '" +
                                                  std::string(origin) + "', host '" + std::string(host) + "')");
  }
  if (!access.required()) {
    if (!loopback_name(host))
      return refusal(http::status::forbidden,
                     "this dashboard answers on loopback only: open it as http://127.0.0.1:" + std::to_string(port) +
                         "/ or http://localhost:" + std::to_string(port) + "/ (host '" + std::string(host) + "')");
    return {};
  }
  const std::size_t query = target.find('?');
  if (query != std::string_view::npos) {
    if (const auto token = pair_value(target.substr(query + 1), "token", '&')) {
      if (!access.admits(*token)) return refusal(http::status::unauthorized, "wrong token");
      if (upgrade) return {};
      return {Admission::Verdict::redirect,
              http::status::see_other,
              {},
              std::string(path),
              token_cookie_name(port) + "=" + std::string(*token) + "; Path=/; HttpOnly; SameSite=Strict"};
    }
  }
  if (const auto cookie = pair_value(view(request[http::field::cookie]), token_cookie_name(port), ';'))
    if (access.admits(*cookie)) return {};
  return refusal(http::status::unauthorized,
                 "this dashboard asks for its token: open it once as http://" + std::string(host) +
                     "/?token=TOKEN, TOKEN being the text of fnet-server's --token-file; the page keeps it in a "
                     "cookie");
}

}  // namespace fnet::web
