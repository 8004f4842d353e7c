#include "server/rpc/connection.hpp"

#include <exception>
#include <optional>
#include <string>

namespace fnet::rpc {
namespace asio = boost::asio;

namespace {

std::atomic<std::uint64_t> next_connection_id{1};

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

Connection::Connection(Strand strand, std::string terminator, const ServerLimits& limits, const Handler& handler,
                       const Access& access, bool authenticated, std::function<void()> on_end)
    : strand_(std::move(strand)),
      limits_(limits),
      terminator_(std::move(terminator)),
      handler_(handler),
      access_(access),
      authenticated_(authenticated || !access.required()),
      on_end_(std::move(on_end)),
      id_(next_connection_id++) {}

Connection::~Connection() {
  if (on_end_) on_end_();
}

void Connection::start() {
  asio::post(strand_, [self = shared_from_this()] { self->read_next(); });
}

void Connection::on_close(std::function<void()> fn) {
  std::unique_lock lock(mutex_);
  if (closed_) {
    lock.unlock();
    fn();
    return;
  }
  close_callbacks_.push_back(std::move(fn));
}

void Connection::take_message(std::string_view text) {
  const bool blank = text.find_first_not_of(" \t\r\n") == std::string_view::npos;
  if (!blank && !run_message(text)) return;  // refused: the connection finishes
  {
    // A client with max_pending_calls calls unanswered is read again when one ends.
    std::lock_guard lock(mutex_);
    read_paused_ = pending_calls_ >= limits_.max_pending_calls;
    if (read_paused_) return;
  }
  if (!closed_) read_next();
}

bool Connection::run_message(std::string_view text) {
  json request;
  std::optional<json> parse_error;
  try {
    request = json::parse(text);
  } catch (const json::parse_error& e) {
    // The library's text ("[json.exception.parse_error.101] ...") is not for users; the byte is.
    parse_error = error_response(nullptr, kParseError,
                                 "parse error: the request is not valid JSON (at byte " + std::to_string(e.byte) + ")");
  }
  if (!parse_error && request.is_object() && request.value("method", json()) == "auth") {
    answer_auth(request);
    return authenticated_;
  }
  if (!authenticated_) {
    const json id = !parse_error && request.is_object() ? request.value("id", json()) : json();
    refuse(error_response(id, kUnauthorized,
                          "unauthorized: this server asks for a token; send "
                          "{\"jsonrpc\":\"2.0\",\"id\":0,\"method\":\"auth\",\"params\":{\"token\":\"...\"}} first "
                          "(fnetctl --token-file FILE or FNET_TOKEN; fnet.Client(token=...))",
                          {{"method", "auth"}}));
    return false;
  }
  if (parse_error) {
    send(*parse_error);
    return true;
  }
  const auto self = shared_from_this();
  if (request.is_array() && request.empty()) {
    send(error_response(nullptr, kInvalidRequest, "empty batch"));
  } else if (request.is_array()) {
    begin_call();
    const auto batch = std::make_shared<Batch>(request.size());
    for (std::size_t k = 0; k < request.size(); ++k)
      dispatch(request[k], handler_, self, [self, batch, k](json one) {
        const std::optional<json> all = batch->put(k, std::move(one));
        if (!all) return;
        if (!all->empty()) self->send(*all);
        self->end_call();
      });
  } else {
    begin_call();
    dispatch(request, handler_, self, [self](json one) {
      if (!one.is_null()) self->send(one);
      self->end_call();
    });
  }
  return true;
}

void Connection::answer_auth(const json& request) {
  const json id = request.value("id", json());
  const json params = request.value("params", json::object());
  const json* token = params.is_object() && params.contains("token") ? &params["token"] : nullptr;
  if (!token || !token->is_string()) {
    if (!authenticated_)
      return refuse(
          error_response(id, kUnauthorized, "unauthorized: auth takes params {\"token\": TEXT}", {{"method", "auth"}}));
    return (void)send(
        error_response(id, kInvalidParams, "auth takes params {\"token\": TEXT}", {{"parameter", "token"}}));
  }
  if (!access_.admits(token->get<std::string>()))
    return refuse(error_response(id, kUnauthorized, "unauthorized: wrong token", {{"method", "auth"}}));
  authenticated_ = true;
  if (request.contains("id")) send(response(id, {{"authenticated", true}}));
}

void Connection::refuse(const json& error) {
  send(error);
  std::lock_guard lock(mutex_);
  close_when_flushed_ = true;
  if (!writing_) asio::post(strand_, [self = shared_from_this()] { self->finish(); });
}

void Connection::input_ended() {
  std::lock_guard lock(mutex_);
  close_when_flushed_ = true;
  if (!writing_ && pending_calls_ == 0) asio::post(strand_, [self = shared_from_this()] { self->close(); });
}

void Connection::begin_call() {
  std::lock_guard lock(mutex_);
  ++pending_calls_;
}

// After the call's response is queued: reading resumes when it waited for this call, and a
// connection whose client has stopped sending finishes once nothing is left to answer or write.
void Connection::end_call() {
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

bool Connection::send(const json& message) {
  std::string text = message.dump(-1, ' ', false, json::error_handler_t::replace);
  text += terminator_;
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

void Connection::write_next() {
  std::lock_guard lock(mutex_);
  if (output_.empty() || !is_open()) {
    writing_ = false;
    return;
  }
  // deque::push_back keeps references valid, so the front string outlives the async write.
  write(output_.front());
}

void Connection::written(const boost::system::error_code& ec) {
  bool more = false, close_now = false;
  {
    std::lock_guard lock(mutex_);
    queued_bytes_ -= output_.front().size();
    output_.pop_front();
    more = !ec && !output_.empty();
    if (!more) writing_ = false;
    close_now = ec || (!more && close_when_flushed_ && pending_calls_ == 0);
  }
  if (ec) return close();
  if (close_now) return finish();
  if (more) write_next();
}

void Connection::close() {
  std::vector<std::function<void()>> callbacks;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    callbacks.swap(close_callbacks_);
  }
  close_transport();
  for (auto& fn : callbacks) fn();
}

}  // namespace fnet::rpc
