// proto/api.md against the methods: every method the server has is documented, with exactly the
// parameters it declares (its `Params:` line), and every request the document shows uses only
// declared parameters of a method that exists.
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <boost/asio/thread_pool.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "server/api/api_methods.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::server {
namespace {

std::string read_doc() {
  std::ifstream in(FNET_API_DOC);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Each "### `method`" section's parameters: the `names` between "Params:" and "Result:".
std::map<std::string, std::set<std::string>> documented_params(const std::string& doc) {
  std::map<std::string, std::set<std::string>> out;
  const std::regex section("\n### `([a-z.]+)`\n");
  const std::regex name("`([a-z_]+)`");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), section); it != std::sregex_iterator(); ++it) {
    const std::size_t at = doc.find("Params:", static_cast<std::size_t>(it->position() + it->length()));
    const std::size_t end = doc.find("Result:", at);
    const std::string text = doc.substr(at, end - at);
    std::set<std::string>& names = out[(*it)[1]];
    for (auto n = std::sregex_iterator(text.begin(), text.end(), name); n != std::sregex_iterator(); ++n)
      names.insert((*n)[1]);
  }
  return out;
}

struct Server {
  testing::TempDir dir;
  boost::asio::thread_pool pool{1};
  Registry registry{dir.path(), pool};
  ApiContext context{registry};
  MethodTable table = method_table(context);
};

TEST(ApiDocument, EveryMethodIsDocumentedWithTheParametersItDeclares) {
  Server server;
  const auto documented = documented_params(read_doc());
  std::set<std::string> names;
  for (const auto& [method, m] : server.table) {
    names.insert(method);
    const auto doc = documented.find(method);
    ASSERT_NE(doc, documented.end()) << method << " has no section in proto/api.md";
    const std::set<std::string> declared(m.params.begin(), m.params.end());
    EXPECT_EQ(doc->second, declared) << method << ": proto/api.md's Params: against the method's declaration";
  }
  for (const auto& [method, params] : documented) EXPECT_TRUE(names.count(method)) << method << " is not a method";
}

TEST(ApiDocument, EveryExampleRequestUsesDeclaredParameters) {
  Server server;
  const std::string doc = read_doc();
  std::istringstream lines(doc);
  std::size_t requests = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("→ ", 0) != 0) continue;
    const auto request = nlohmann::json::parse(line.substr(std::string("→ ").size()));
    ++requests;
    const std::string method = request.at("method");
    const auto m = server.table.find(method);
    ASSERT_NE(m, server.table.end()) << line;
    // An example of the unknown-parameter error lists what the method declares.
    std::string answer;
    std::getline(lines, answer);
    const auto response = nlohmann::json::parse(answer.substr(answer.find('{')));
    std::string rejected;
    if (response.contains("error") && response["error"].contains("data") &&
        response["error"]["data"].contains("accepted")) {
      rejected = response["error"]["data"]["parameter"];
      const std::vector<std::string> accepted = response["error"]["data"]["accepted"];
      EXPECT_EQ(accepted, std::vector<std::string>(m->second.params.begin(), m->second.params.end())) << answer;
    }
    if (!request.contains("params")) continue;
    const nlohmann::json& params = request["params"];
    for (auto p = params.begin(); p != params.end(); ++p) {
      if (p.key() == rejected) continue;
      EXPECT_NE(std::find(m->second.params.begin(), m->second.params.end(), p.key()), m->second.params.end())
          << method << " example uses '" << p.key() << "', which it does not declare";
    }
  }
  EXPECT_GE(requests, server.table.size()) << "an example request per method at least";
}

}  // namespace
}  // namespace fnet::server
