// Who may open the dashboard (rpc::Access over HTTP). With a token: the page is opened once with
// ?token=TOKEN, answered with a redirect that drops it from the address and sets it as a cookie
// (HttpOnly, SameSite=Strict) that every later request, the WebSocket's included, carries; a
// request with neither gets 401. Without a token the server listens on loopback only, and answers
// only requests addressed to a loopback host name (a page of another site that rebinds its name
// to 127.0.0.1 gets 403). A WebSocket upgrade must come from a page of this server (its Origin,
// when sent, is the request's Host), so that another site's page cannot open it in the browser.
#pragma once

#include <string>
#include <string_view>

#include <boost/beast/http.hpp>

#include "server/rpc/access.hpp"

namespace fnet::web {

struct Admission {
  enum class Verdict { admit, redirect, refuse } verdict = Verdict::admit;
  boost::beast::http::status status = boost::beast::http::status::ok;  // of a refusal
  std::string message;                                                 // why refused
  std::string location, set_cookie;                                    // of a redirect
};

// The cookie that carries the token of the server listening on `port` (one per port, so that two
// servers on one host keep theirs apart).
std::string token_cookie_name(unsigned short port);

// What to do with `request`, a request to the server listening on `port`.
Admission admit(const boost::beast::http::request<boost::beast::http::string_body>& request, const rpc::Access& access,
                unsigned short port);

}  // namespace fnet::web
