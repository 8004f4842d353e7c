#include "server/rpc/access.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <boost/asio/ip/address.hpp>

namespace fnet::rpc {

bool Access::admits(std::string_view given) const { return !required() || same_secret(token, given); }

bool same_secret(std::string_view secret, std::string_view given) {
  // Every byte of `given` is compared (against the secret, cyclically), whatever it holds.
  unsigned difference = secret.size() == given.size() ? 0u : 1u;
  if (secret.empty()) return given.empty();
  for (std::size_t k = 0; k < given.size(); ++k)
    difference |= static_cast<unsigned char>(secret[k % secret.size()]) ^ static_cast<unsigned char>(given[k]);
  return difference == 0;
}

std::string read_token_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the token file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  std::string token = text.str();
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r')) token.pop_back();
  const auto allowed = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '~' || c == '-';
  };
  for (std::size_t k = 0; k < token.size(); ++k)
    if (!allowed(token[k]))
      throw std::runtime_error("token file '" + path + "': character " + std::to_string(k + 1) +
                               " is not one of A-Z a-z 0-9 . _ ~ - (the token is one line)");
  if (token.size() < kMinTokenLength)
    throw std::runtime_error("token file '" + path + "': the token has " + std::to_string(token.size()) +
                             " characters, fewer than " + std::to_string(kMinTokenLength) +
                             " (make one with: head -c 32 /dev/urandom | base64 | tr '+/' '-_' | tr -d '=')");
  return token;
}

bool is_loopback(const std::string& address) {
  boost::system::error_code ec;
  const auto ip = boost::asio::ip::make_address(address, ec);
  return !ec && ip.is_loopback();
}

}  // namespace fnet::rpc
