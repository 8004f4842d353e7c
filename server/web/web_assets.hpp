// The dashboard's page and scripts (client/web/), embedded in fnet-server when it is built, so
// that the page a server serves always speaks that server's API and needs no installed files.
#pragma once

#include <string_view>

namespace fnet::web {

struct Asset {
  std::string_view path;  // "/index.html", "/dashboard.js", ...
  std::string_view content_type;
  std::string_view body;
};

// The asset served at `path` ("/" is "/index.html"); null when there is none.
const Asset* find_asset(std::string_view path);

}  // namespace fnet::web
