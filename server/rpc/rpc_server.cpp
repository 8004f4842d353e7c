#include "server/rpc/rpc_server.hpp"

#include <array>
#include <atomic>
#include <exception>
#include <istream>
#include <optional>
#include <stdexcept>
#include <string>

namespace fnet::rpc {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace {

std::atomic<std::uint64_t> next_session_id{1};

// The response to a call that ended with `result` or `error`; null for a notification.
json answer(const json& id, bool has_id, json result, const std::exception_ptr& error) {
  if (!has_id) return json();
  if (!error) return response(id, std::move(result));
  try {
    std::rethrow_exception(error);
  } catch (const Error& e) {
    return error_response(id, e.code(), e.what(), e.data());
  } catch (const json::exception&) {
    // Handlers check every parameter's type; reaching here is a bug, not the client's fault.
    return error_response(id, kInternalError, "internal error while reading the params");
  } catch (const std::exception& e) {
    return error_response(id, kInternalError, e.what());
  } catch (...) {
    return error_response(id, kInternalError, "internal error");
  }
}

// Validates one request object and runs it; `reply` gets its response (null for a notification)
// exactly once, at once or from the thread that ends the call.
void dispatch(const json& request, const Handler& handler, const std::shared_ptr<Peer>& peer,
              const std::function<void(json)>& reply) {
  const bool has_id = request.is_object() && request.contains("id");
  const json id = has_id ? request["id"] : json(nullptr);
  if (!request.is_object()) return reply(error_response(nullptr, kInvalidRequest, "a request must be a JSON object"));
  if (has_id && !(id.is_string() || id.is_number_integer() || id.is_null()))
    return reply(error_response(nullptr, kInvalidRequest, "'id' must be a string, an integer or null"));
  if (request.value("jsonrpc", json()) != "2.0")
    return reply(error_response(id, kInvalidRequest, "'jsonrpc' must be \"2.0\""));
  if (!request.contains("method") || !request["method"].is_string())
    return reply(error_response(id, kInvalidRequest, "'method' must be a string"));
  const json params = request.value("params", json::object());
  if (!params.is_object() && !params.is_array())
    return reply(error_response(id, kInvalidRequest, "'params' must be an object or an array"));
  const auto ended = std::make_shared<std::atomic<bool>>(false);
  const Completion done = [reply, id, has_id, ended](json result, std::exception_ptr error) {
    if (!ended->exchange(true)) reply(answer(id, has_id, std::move(result), error));
  };
  try {
    handler(request["method"].get<std::string>(), params, peer, done);
  } catch (...) {
    done(nullptr, std::current_exception());
  }
}

// The responses of one batch, sent together once every call of it has ended.
class Batch {
 public:
  explicit Batch(std::size_t calls) : slots_(calls), remaining_(calls) {}
  // Returns the responses to send when this was the batch's last call.
  std::optional<json> put(std::size_t k, json response) {
    std::lock_guard lock(mutex_);
    slots_[k] = std::move(response);
    if (--remaining_ > 0) return std::nullopt;
    json all = json::array();
    for (json& r : slots_)
      if (!r.is_null()) all.push_back(std::move(r));
    return all;
  }

 private:
  std::mutex mutex_;
  std::vector<json> slots_;
  std::size_t remaining_;
};

}  // namespace

Session::Session(tcp::socket socket, const ServerLimits& limits, const Handler& handler, std::function<void()> on_end)
    : socket_(std::move(socket)),
      strand_(asio::make_strand(socket_.get_executor())),
      input_(limits.max_line_bytes + 1),
      limits_(limits),
      handler_(handler),
      on_end_(std::move(on_end)),
      id_(next_session_id++) {}

Session::~Session() {
  if (on_end_) on_end_();
}

void Session::start() {
  asio::post(strand_, [self = shared_from_this()] { self->read_next(); });
}

void Session::on_close(std::function<void()> fn) {
  std::unique_lock lock(mutex_);
  if (closed_) {
    lock.unlock();
    fn();
    return;
  }
  close_callbacks_.push_back(std::move(fn));
}

void Session::read_next() {
  asio::async_read_until(
      socket_, input_, '\n',
      asio::bind_executor(strand_, [self = shared_from_this()](boost::system::error_code ec, std::size_t n) {
        if (ec == asio::error::not_found) {  // the line outgrew the buffer's limit
          self->send(error_response(nullptr, kInvalidRequest,
                                    "request line longer than " + std::to_string(self->limits_.max_line_bytes) +
                                        " bytes; closing the connection"));
          std::lock_guard lock(self->mutex_);
          self->close_when_flushed_ = true;
          if (!self->writing_) asio::post(self->strand_, [self] { self->finish(); });
          return;
        }
        if (ec == asio::error::eof) {  // the client is done sending: answer what it asked, then close
          std::lock_guard lock(self->mutex_);
          self->close_when_flushed_ = true;
          if (!self->writing_ && self->pending_calls_ == 0) asio::post(self->strand_, [self] { self->close(); });
          return;
        }
        if (ec) return self->close();
        std::string line(n, '\0');
        std::istream(&self->input_).read(line.data(), static_cast<std::streamsize>(n));
        line.pop_back();  // '\n'
        if (!line.empty() && line.back() == '\r') line.pop_back();
        self->handle_line(line);
        {
          // A client with max_pending_calls calls unanswered is read again when one ends.
          std::lock_guard lock(self->mutex_);
          self->read_paused_ = self->pending_calls_ >= self->limits_.max_pending_calls;
          if (self->read_paused_) return;
        }
        if (!self->closed_) self->read_next();
      }));
}

void Session::handle_line(const std::string& line) {
  if (line.find_first_not_of(" \t") == std::string::npos) return;
  json request;
  try {
    request = json::parse(line);
  } catch (const json::parse_error& e) {
    // The library's text ("[json.exception.parse_error.101] ...") is not for users; the byte is.
    send(error_response(nullptr, kParseError,
                        "parse error: the request is not valid JSON (at byte " + std::to_string(e.byte) + ")"));
    return;
  }
  const auto self = shared_from_this();
  if (request.is_array() && request.empty()) {
    send(error_response(nullptr, kInvalidRequest, "empty batch"));
    return;
  }
  begin_call();
  if (request.is_array()) {
    const auto batch = std::make_shared<Batch>(request.size());
    for (std::size_t k = 0; k < request.size(); ++k)
      dispatch(request[k], handler_, self, [self, batch, k](json one) {
        const std::optional<json> all = batch->put(k, std::move(one));
        if (!all) return;
        if (!all->empty()) self->send(*all);
        self->end_call();
      });
    return;
  }
  dispatch(request, handler_, self, [self](json one) {
    if (!one.is_null()) self->send(one);
    self->end_call();
  });
}

void Session::begin_call() {
  std::lock_guard lock(mutex_);
  ++pending_calls_;
}

// After the call's response is queued: reading resumes when it waited for this call, and a
// connection whose client has stopped sending finishes once nothing is left to answer or write.
void Session::end_call() {
  bool resume = false, finish_now = false;
  {
    std::lock_guard lock(mutex_);
    --pending_calls_;
    if (read_paused_ && pending_calls_ < limits_.max_pending_calls) {
      read_paused_ = false;
      resume = !close_when_flushed_;
    }
    finish_now = close_when_flushed_ && pending_calls_ == 0 && !writing_ && !closed_;
  }
  if (resume) asio::post(strand_, [self = shared_from_this()] { self->read_next(); });
  if (finish_now) asio::post(strand_, [self = shared_from_this()] { self->finish(); });
}

bool Session::send(const json& message) {
  std::string text = message.dump(-1, ' ', false, json::error_handler_t::replace);
  text.push_back('\n');
  std::lock_guard lock(mutex_);
  if (closed_) return false;
  if (queued_bytes_ + text.size() > limits_.max_queued_bytes) {
    // A client that does not read its output is dropped rather than buffered without bound.
    asio::post(strand_, [self = shared_from_this()] { self->close(); });
    closed_ = true;
    return false;
  }
  queued_bytes_ += text.size();
  output_.push_back(std::move(text));
  if (!writing_) {
    writing_ = true;
    asio::post(strand_, [self = shared_from_this()] { self->write_next(); });
  }
  return true;
}

void Session::write_next() {
  std::lock_guard lock(mutex_);
  if (output_.empty() || !socket_.is_open()) {
    writing_ = false;
    return;
  }
  // deque::push_back keeps references valid, so the front string outlives the async write.
  asio::async_write(
      socket_, asio::buffer(output_.front()),
      asio::bind_executor(strand_, [self = shared_from_this()](boost::system::error_code ec, std::size_t) {
        bool more = false, close_now = false;
        {
          std::lock_guard inner(self->mutex_);
          self->queued_bytes_ -= self->output_.front().size();
          self->output_.pop_front();
          more = !ec && !self->output_.empty();
          if (!more) self->writing_ = false;
          close_now = ec || (!more && self->close_when_flushed_ && self->pending_calls_ == 0);
        }
        if (ec) return self->close();
        if (close_now) return self->finish();
        if (more) self->write_next();
      }));
}

// After the last reply: half-close, then discard what the client is still sending (for at most
// a few seconds) so that closing does not reset the connection and destroy the reply in flight.
void Session::finish() {
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_send, ignored);
  auto timer = std::make_shared<asio::steady_timer>(socket_.get_executor(), std::chrono::seconds(3));
  timer->async_wait(
      asio::bind_executor(strand_, [self = shared_from_this(), timer](boost::system::error_code) { self->close(); }));
  drain(timer);
}

void Session::drain(const std::shared_ptr<asio::steady_timer>& timer) {
  auto buffer = std::make_shared<std::array<char, 65536>>();
  socket_.async_read_some(asio::buffer(*buffer),
                          asio::bind_executor(strand_, [self = shared_from_this(), buffer, timer](
                                                           boost::system::error_code ec, std::size_t) {
                            if (ec) {
                              timer->cancel();
                              return self->close();
                            }
                            self->drain(timer);
                          }));
}

void Session::close() {
  std::vector<std::function<void()>> callbacks;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    callbacks.swap(close_callbacks_);
  }
  boost::system::error_code ignored;
  socket_.shutdown(tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  for (auto& fn : callbacks) fn();
}

Server::Server(asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
               ServerLimits limits)
    : io_(io), acceptor_(io), handler_(std::move(handler)), limits_(limits) {
  boost::system::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(address, ec);
  if (ec) throw std::runtime_error("cannot listen on '" + address + "': not an IP address");
  const tcp::endpoint endpoint(ip, port);
  // Whoever owns the port must be named: a user meeting "address in use" has to find it.
  const auto fail = [&](const char* step) {
    throw std::runtime_error("cannot listen on " + address + ":" + std::to_string(port) + ": " + step + ": " +
                             ec.message());
  };
  // (Each call then a test of ec: newer Boost returns void from the error_code overloads.)
  acceptor_.open(endpoint.protocol(), ec);
  if (ec) fail("open");
  acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
  if (ec) fail("setsockopt");
  acceptor_.bind(endpoint, ec);
  if (ec) fail("bind");
  acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) fail("listen");
  accept_next();
}

unsigned short Server::port() const { return acceptor_.local_endpoint().port(); }

void Server::stop() {
  boost::system::error_code ignored;
  acceptor_.close(ignored);
}

void Server::accept_next() {
  acceptor_.async_accept(asio::make_strand(io_), [this](boost::system::error_code ec, tcp::socket socket) {
    if (ec == asio::error::operation_aborted) return;
    if (!ec) {
      if (connections_ >= limits_.max_connections) {
        const std::string refusal =
            error_response(nullptr, kServerBusy,
                           "too many connections (" + std::to_string(limits_.max_connections) + ")")
                .dump() +
            "\n";
        boost::system::error_code ignored;
        socket.non_blocking(true, ignored);
        socket.write_some(asio::buffer(refusal), ignored);
        socket.close(ignored);
      } else {
        ++connections_;
        std::make_shared<Session>(std::move(socket), limits_, handler_, [this] { --connections_; })->start();
      }
    }
    accept_next();
  });
}

}  // namespace fnet::rpc
