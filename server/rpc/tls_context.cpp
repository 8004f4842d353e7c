#include "server/rpc/tls_context.hpp"

#include <stdexcept>

namespace fnet::rpc {
namespace ssl = boost::asio::ssl;

TlsContext make_server_tls(const std::string& cert_file, const std::string& key_file) {
  auto tls = std::make_shared<ssl::context>(ssl::context::tls_server);
  tls->set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 | ssl::context::no_sslv3 |
                   ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1 | ssl::context::single_dh_use);
  boost::system::error_code ec;
  tls->use_certificate_chain_file(cert_file, ec);
  if (ec) throw std::runtime_error("cannot use '" + cert_file + "' as a PEM certificate chain: " + ec.message());
  tls->use_private_key_file(key_file, ssl::context::pem, ec);
  if (ec)
    throw std::runtime_error("cannot use '" + key_file + "' as the PEM private key of '" + cert_file +
                             "': " + ec.message());
  return tls;
}

}  // namespace fnet::rpc
