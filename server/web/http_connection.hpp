// One HTTP connection of the dashboard: requests read one after another (keep-alive), each
// admitted or not (http_access.hpp), then answered with an asset, an error status, or, for
// kRpcPath, handed over to a WebSocket peer.
#pragma once

#include <memory>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>

#include "server/rpc/connection.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::web {

using Request = boost::beast::http::request<boost::beast::http::string_body>;
using Response = boost::beast::http::response<boost::beast::http::string_body>;

// The answer to a request that is not a WebSocket upgrade: an asset for GET, else a 4xx status
// whose body says what is wrong.
Response answer(const Request& request);

using TlsStream = boost::beast::ssl_stream<boost::beast::tcp_stream>;

// `Stream`: boost::beast::tcp_stream (http, ws) or TlsStream (https, wss), whose handshake must
// end within first_request_timeout, else the connection is closed and its slot freed.
template <class Stream>
class HttpConnection : public std::enable_shared_from_this<HttpConnection<Stream>> {
 public:
  // `slot` is held while the connection lives (its WebSocket peer included): the count of
  // connections goes down when the last holder ends.
  HttpConnection(Stream stream, rpc::Strand strand, const rpc::ServerLimits& limits, const rpc::Handler& handler,
                 const rpc::Access& access, unsigned short port, std::shared_ptr<void> slot);
  // The TLS handshake if any, then the first request.
  void start();

 private:
  void read_request();
  void on_request(boost::beast::error_code ec);
  void send(Response response);
  void close();
  void drain();
  boost::beast::tcp_stream& tcp() { return boost::beast::get_lowest_layer(stream_); }

  Stream stream_;
  rpc::Strand strand_;
  boost::beast::flat_buffer buffer_;
  std::unique_ptr<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  const rpc::ServerLimits& limits_;
  const rpc::Handler& handler_;
  const rpc::Access& access_;
  const unsigned short port_;  // the server's, which names its token's cookie
  std::shared_ptr<void> slot_;
};

}  // namespace fnet::web
