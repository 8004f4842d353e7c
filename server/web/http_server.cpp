#include "server/web/http_server.hpp"

#include <string>

#include "server/web/http_connection.hpp"

namespace fnet::web {

namespace {
const std::string kBusy =
    "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\nConnection: close\r\nContent-Length: "
    "21\r\n\r\ntoo many connections\n";
}

HttpServer::HttpServer(boost::asio::io_context& io, const std::string& address, unsigned short port,
                       rpc::Handler handler, rpc::ServerLimits limits, rpc::Access access, rpc::TlsContext tls)
    : handler_(std::move(handler)),
      limits_(limits),
      access_(std::move(access)),
      tls_(std::move(tls)),
      listener_(
          io, address, port, limits_.max_connections, tls_ ? "" : kBusy,
          [this](boost::asio::ip::tcp::socket socket, rpc::Strand strand, std::shared_ptr<void> slot) {
            boost::beast::tcp_stream stream(std::move(socket));
            if (tls_)
              std::make_shared<HttpConnection<TlsStream>>(TlsStream(std::move(stream), *tls_), std::move(strand),
                                                          limits_, handler_, access_, listener_.port(), std::move(slot))
                  ->start();
            else
              std::make_shared<HttpConnection<boost::beast::tcp_stream>>(
                  std::move(stream), std::move(strand), limits_, handler_, access_, listener_.port(), std::move(slot))
                  ->start();
          }) {}

}  // namespace fnet::web
