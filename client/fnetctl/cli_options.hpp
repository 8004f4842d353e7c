// What fnetctl's commands share: exit codes, where the server is, and the checks that turn a
// typed value into what it names (the vocabulary of common/analysis) or a usage error naming the
// flag. Usage errors are boost::program_options::error; main() turns them into exit code 2.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "client/rpc/rpc_client.hpp"
#include "common/analysis/metric_vocabulary.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/force_network.hpp"

namespace fnet::client {

// Documented in --help and deploy/README.md (exit codes).
enum Exit : int { kOk = 0, kFailure = 1, kUsage = 2, kUnreachable = 3, kUnknown = 4, kServerError = 5 };

struct Endpoint {
  std::string host = "127.0.0.1";
  unsigned short port = 7707;
  std::string token;  // presented first when not empty (a server given --token-file asks for it)
  TlsOptions tls;     // --tls, --tls-ca FILE (which implies --tls)
};

// The server's address and token: FNET_HOST / FNET_PORT / FNET_TOKEN from the environment,
// overridden by --host, --port, --token-file, --tls and --tls-ca (also --host=H, ...) wherever they stand on the
// command line; those are removed from `args`. Throws boost::program_options::error naming the
// flag or variable (a token file that cannot be read, too).
Endpoint take_endpoint(std::vector<std::string>& args, const char* env_host, const char* env_port,
                       const char* env_token = nullptr);

// Parses a command's options; false after printing --help. `vm`, when given, receives the values.
bool parse_command(const boost::program_options::options_description& options, const std::vector<std::string>& args,
                   boost::program_options::variables_map* vm = nullptr);

// Each throws boost::program_options::error naming the flag and the value.
MetricChoice metric_option(const std::string& name, std::optional<double> q);
int dim_option(long long dim);
ForceKind force_option(const std::string& name);
EssentialConvention essential_option(const std::string& name);
std::uint32_t frame_option(const char* flag, long long value);
void format_option(const std::string& format, std::initializer_list<const char*> allowed);

// The options that select a diagram series (--run, --dim, --force and, with a metric, --metric,
// --q, --essential), as typed; checked() turns them into API parameters or throws a usage error
// naming the flag. Every command that reads one series or frame pair takes them.
struct SeriesOptions {
  std::string run, force = "normal", essential = "floor", metric;
  long long dim = kDefaultDim;
  double q = 0;

  // Adds --help too. `metric_required` false: the command checks --metric itself (query: --ratio
  // stands in for it).
  void add(boost::program_options::options_description& o, bool with_metric, bool metric_required = true);
  nlohmann::json checked(const boost::program_options::variables_map& vm) const;
};

}  // namespace fnet::client
