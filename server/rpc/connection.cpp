#include "server/rpc/connection.hpp"

#include <algorithm>
#include <exception>
#include <optional>
#include <sstream>
#include <string>

#include "common/codec/bounded_json.hpp"

namespace fnet::rpc {
namespace asio = boost::asio;

namespace {

std::atomic<std::uint64_t> next_connection_id{1};

// How often a connection's deadlines are checked: each is met within a tick.
constexpr auto kTick = std::chrono::milliseconds(250);

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

json limit_error(const json& id, const char* limit, json value, const std::string& message) {
  return error_response(id, kLimitExceeded, message, {{"limit", limit}, {"value", std::move(value)}});
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

// The error for a message the client sent that cannot be read as JSON within the limits.
json unreadable(const JsonInputError& e, std::size_t max_depth) {
  if (e.kind() == JsonInputError::Kind::too_deep)
    return limit_error(nullptr, "max_json_depth", max_depth, "the request is " + e.reason());
  return error_response(nullptr, kParseError, "parse error: " + e.reason());
}

// "10", "0.5": seconds as a user wrote them.
std::string seconds_text(Seconds s) {
  std::ostringstream out;
  out << s.count();
  return out.str();
}

// An answer (or a batch of answers) replaced by the error `make` builds for each id; a
// notification replaced by one error without id.
json replaced(const json& message, const std::function<json(const json& id)>& make) {
  if (message.is_array()) {
    json all = json::array();
    for (const json& one : message) all.push_back(make(one.is_object() ? one.value("id", json()) : json()));
    return all;
  }
  return make(message.is_object() ? message.value("id", json()) : json());
}

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
      ticker_(strand_),
      id_(next_connection_id++) {}

Connection::~Connection() {
  if (on_end_) on_end_();
}

void Connection::start() {
  asio::post(strand_, [self = shared_from_this()] {
    self->tick();
    self->read_if_room();
  });
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

void Connection::read_if_room() {
  if (closed_ || reading_ || !waiting_.empty()) return;
  {
    std::lock_guard lock(mutex_);
    // A client whose answers wait unread past the bound is not read until it reads them.
    if (close_when_flushed_ || in_progress_ >= limits_.max_calls_in_progress ||
        queued_bytes_ >= limits_.max_queued_bytes)
      return;
  }
  reading_ = true;
  read_next();
}

void Connection::take_message(std::string_view text) {
  reading_ = false;
  input_since_.reset();
  got_message_ = true;
  {
    std::lock_guard lock(mutex_);
    last_activity_ = Clock::now();
  }
  const bool blank = text.find_first_not_of(" \t\r\n") == std::string_view::npos;
  if (!blank && !run_message(text)) return;  // refused: the connection finishes
  start_calls();
  read_if_room();
}

bool Connection::run_message(std::string_view text) {
  json request;
  std::optional<json> parse_error;
  try {
    // The transports bound a message's bytes as they read it (max_line_bytes).
    request = parse_bounded_json(text, JsonLimits{text.size(), limits_.max_json_depth}, "the request");
  } catch (const JsonInputError& e) {
    parse_error = unreadable(e, limits_.max_json_depth);
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
  } else if (request.is_array() && request.size() > limits_.max_batch_calls) {
    send(limit_error(nullptr, "max_batch_calls", limits_.max_batch_calls,
                     "a batch of " + std::to_string(request.size()) + " calls; at most " +
                         std::to_string(limits_.max_batch_calls) + " per batch (none of it ran)"));
  } else if (request.is_array()) {
    const auto batch = std::make_shared<Batch>(request.size());
    for (std::size_t k = 0; k < request.size(); ++k)
      waiting_.push_back({std::move(request[k]), [self, batch, k](json one) {
                            const std::optional<json> all = batch->put(k, std::move(one));
                            if (all && !all->empty()) self->send(*all);
                            self->end_call();
                          }});
  } else {
    waiting_.push_back({std::move(request), [self](json one) {
                          if (!one.is_null()) self->send(one);
                          self->end_call();
                        }});
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

void Connection::start_calls() {
  if (starting_) return;  // a call that ended at once: the loop below goes on
  starting_ = true;
  const auto self = shared_from_this();
  while (!waiting_.empty() && !closed_) {
    {
      std::lock_guard lock(mutex_);
      if (in_progress_ >= limits_.max_calls_in_progress) break;
      ++in_progress_;
    }
    Call call = std::move(waiting_.front());
    waiting_.pop_front();
    dispatch(call.request, handler_, self, call.reply);
  }
  starting_ = false;
}

void Connection::refuse(const json& error) { refuse_text(error.dump() + terminator_); }

void Connection::refuse_text(std::string text) {
  waiting_.clear();
  reading_ = false;
  std::lock_guard lock(mutex_);
  if (closed_) return;
  close_when_flushed_ = true;
  queued_bytes_ += text.size();  // past the bound if need be: the last words are short
  output_.push_back(std::move(text));
  if (!writing_) {
    writing_ = true;
    last_write_ = Clock::now();
    asio::post(strand_, [self = shared_from_this()] { self->write_next(); });
  }
}

void Connection::input_ended() {
  reading_ = false;
  {
    std::lock_guard lock(mutex_);
    close_when_flushed_ = true;
  }
  after_call();
}

// Off the strand (a heavy call ends on the analysis pool): the rest is the strand's.
void Connection::end_call() {
  {
    std::lock_guard lock(mutex_);
    --in_progress_;
    last_activity_ = Clock::now();
  }
  asio::post(strand_, [self = shared_from_this()] { self->after_call(); });
}

void Connection::after_call() {
  if (closed_) return;
  start_calls();
  read_if_room();
  bool finish_now = false;
  {
    std::lock_guard lock(mutex_);
    finish_now = close_when_flushed_ && in_progress_ == 0 && waiting_.empty() && !writing_;
  }
  if (finish_now) finish();
}

bool Connection::send(const json& message) {
  std::string text = message.dump(-1, ' ', false, json::error_handler_t::replace);
  text += terminator_;
  std::lock_guard lock(mutex_);
  if (closed_) return false;
  const bool answer = message.is_array() || message.contains("id");
  if (close_when_flushed_ && !answer) return false;  // the connection is saying its last words
  const char* limit = nullptr;
  std::size_t value = 0;
  std::string why;
  if (text.size() > limits_.max_answer_bytes) {
    limit = "max_answer_bytes";
    value = limits_.max_answer_bytes;
    why = "the answer has " + std::to_string(text.size()) + " bytes; at most " + std::to_string(value) +
          " are sent: ask for less (a frame range, fewer calls per batch)";
  } else if (queued_bytes_ + text.size() > limits_.max_queued_bytes) {
    limit = "max_queued_bytes";
    value = limits_.max_queued_bytes;
    why = answer ? "the answer (" + std::to_string(text.size()) +
                       " bytes) would take this connection's unread output past " + std::to_string(value) +
                       " bytes: read the answers already sent"
                 : "unread output past " + std::to_string(value) +
                       " bytes: the notifications after it would be lost; closing the connection";
  }
  if (limit) {
    // Short: queued whatever the bound, which it passes by at most one such line per call in progress.
    text = replaced(message, [&](const json& id) { return limit_error(id, limit, value, why); }).dump() + terminator_;
    if (!answer) close_when_flushed_ = true;  // a notification cannot be replaced: the client would miss it
  }
  queued_bytes_ += text.size();
  output_.push_back(std::move(text));
  if (!writing_) {
    writing_ = true;
    last_write_ = Clock::now();
    asio::post(strand_, [self = shared_from_this()] { self->write_next(); });
  }
  return true;
}

// What subscriptions may leave unread: at most a quarter of the bound, so answers keep their room.
std::size_t Connection::window() const { return std::min(limits_.subscription_window, limits_.max_queued_bytes / 4); }

bool Connection::wait_for_room(std::function<void()> resume) {
  std::lock_guard lock(mutex_);
  if (closed_) return false;
  if (queued_bytes_ < window()) return true;
  resume_ = std::move(resume);
  return false;
}

void Connection::subscriptions_changed(int delta) {
  std::lock_guard lock(mutex_);
  subscriptions_ += delta;
  last_activity_ = Clock::now();
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
  std::function<void()> resume;
  {
    std::lock_guard lock(mutex_);
    queued_bytes_ -= output_.front().size();
    output_.pop_front();
    last_write_ = Clock::now();
    more = !ec && !output_.empty();
    if (!more) writing_ = false;
    close_now = ec || (!more && close_when_flushed_ && in_progress_ == 0 && waiting_.empty());
    if (resume_ && !ec && queued_bytes_ <= window() / 2) resume.swap(resume_);
  }
  if (resume) resume();
  if (ec) return close();
  if (close_now) return finish();
  read_if_room();
  if (more) write_next();
}

void Connection::tick() {
  if (closed_) return;
  const auto now = Clock::now();
  const auto past = [&](Clock::time_point since, Seconds limit) { return now - since > limit; };
  if (!partial_input()) {
    input_since_.reset();
  } else if (!input_since_) {
    input_since_ = now;
  } else if (past(*input_since_, limits_.request_timeout)) {
    return expire("request_timeout", limits_.request_timeout,
                  "a request begun is not complete; closing the connection");
  }
  if (!got_message_ && !input_since_ && past(opened_, limits_.first_request_timeout))
    return expire("first_request_timeout", limits_.first_request_timeout,
                  "no request since the connection opened; closing it");
  bool idle = false, stalled = false;
  {
    std::lock_guard lock(mutex_);
    stalled = writing_ && past(last_write_, limits_.write_timeout);
    idle = got_message_ && in_progress_ == 0 && subscriptions_ == 0 && output_.empty() && waiting_.empty() &&
           !input_since_ && past(last_activity_, limits_.idle_timeout);
  }
  if (stalled) return close();  // a client that does not read cannot be told
  if (idle)
    return expire("idle_timeout", limits_.idle_timeout,
                  "idle: no request, nothing in progress and no subscription; closing the connection");
  ticker_.expires_after(kTick);
  ticker_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
    if (!ec) self->tick();
  });
}

void Connection::expire(const char* limit, Seconds value, const std::string& message) {
  refuse(limit_error(nullptr, limit, value.count(), message + " (" + seconds_text(value) + " s, " + limit + ")"));
}

void Connection::close() {
  std::vector<std::function<void()>> callbacks;
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
    callbacks.swap(close_callbacks_);
    resume_ = nullptr;
  }
  waiting_.clear();
  ticker_.cancel();
  close_transport();
  for (auto& fn : callbacks) fn();
}

}  // namespace fnet::rpc
