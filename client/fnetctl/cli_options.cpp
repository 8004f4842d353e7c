#include "client/fnetctl/cli_options.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "common/codec/command_line.hpp"

namespace fnet::client {

namespace po = boost::program_options;

namespace {

unsigned short parse_port(const std::string& text, const std::string& source) {
  unsigned long port = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), port);
  if (ec != std::errc() || end != text.data() + text.size() || port == 0 || port > 65535)
    throw po::error(source + " must be an integer in 1..65535, got '" + text + "'");
  return static_cast<unsigned short>(port);
}

// Rethrows the vocabulary's std::invalid_argument as a usage error naming `flag`.
template <class Parse>
auto named(const std::string& flag, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw po::error(flag + ": " + e.what());
  }
}

// The first line of a token file, without its line end.
std::string read_token(const std::string& path) {
  std::ifstream in(path);
  std::string token;
  if (!in || !std::getline(in, token)) throw po::error("--token-file: cannot read '" + path + "'");
  if (!token.empty() && token.back() == '\r') token.pop_back();
  if (token.empty()) throw po::error("--token-file: '" + path + "' holds no token on its first line");
  return token;
}

}  // namespace

Endpoint take_endpoint(std::vector<std::string>& args, const char* env_host, const char* env_port,
                       const char* env_token) {
  Endpoint at;
  if (env_host && *env_host) at.host = env_host;
  if (env_port && *env_port) at.port = parse_port(env_port, "FNET_PORT");
  if (env_token && *env_token) at.token = env_token;
  std::vector<std::string> rest;
  for (std::size_t k = 0; k < args.size(); ++k) {
    // The value of `flag` when args[k] is "flag VALUE" or "flag=VALUE".
    const auto value_of = [&](const std::string& flag) -> std::optional<std::string> {
      if (args[k] == flag) {
        if (k + 1 >= args.size()) throw po::error(flag + " needs a value");
        return args[++k];
      }
      if (args[k].rfind(flag + "=", 0) == 0) return args[k].substr(flag.size() + 1);
      return std::nullopt;
    };
    if (const auto host = value_of("--host")) {
      if (host->empty()) throw po::error("--host needs a host name or address");
      at.host = *host;
    } else if (const auto port = value_of("--port")) {
      at.port = parse_port(*port, "--port");
    } else if (const auto file = value_of("--token-file")) {
      at.token = read_token(*file);
    } else if (args[k] == "--tls") {
      at.tls.enabled = true;
    } else if (const auto ca = value_of("--tls-ca")) {
      if (ca->empty()) throw po::error("--tls-ca needs a file of PEM certificates");
      at.tls = {true, *ca};
    } else {
      rest.push_back(args[k]);
    }
  }
  args = std::move(rest);
  return at;
}

bool parse_command(const po::options_description& options, const std::vector<std::string>& args,
                   po::variables_map* out) {
  po::variables_map vm;
  const po::parsed_options parsed = po::command_line_parser(args).options(options).run();
  refuse_stray_arguments(parsed);
  po::store(parsed, vm);
  if (vm.count("help")) {
    std::cout << options << "\n";
    return false;
  }
  po::notify(vm);
  if (out) *out = std::move(vm);
  return true;
}

MetricChoice metric_option(const std::string& name, std::optional<double> q) {
  const bool known = std::find(kMetricNames.begin(), kMetricNames.end(), name) != kMetricNames.end();
  // A known name fails only for its exponent.
  return named(known ? "--q" : "--metric", [&] { return parse_metric(name, q); });
}

int dim_option(long long dim) {
  return named("--dim", [&] { return check_dim(dim); });
}

ForceKind force_option(const std::string& name) {
  return named("--force", [&] { return parse_force_kind(name); });
}

EssentialConvention essential_option(const std::string& name) {
  return named("--essential", [&] { return parse_essential_convention(name); });
}

std::uint32_t frame_option(const char* flag, long long value) {
  if (value < 0 || value > static_cast<long long>(UINT32_MAX))
    throw po::error(std::string(flag) + " must be a frame index (0, 1, ...), got " + std::to_string(value));
  return static_cast<std::uint32_t>(value);
}

void format_option(const std::string& format, std::initializer_list<const char*> allowed) {
  std::string names;
  for (const char* a : allowed) {
    if (format == a) return;
    names += (names.empty() ? "" : ", ") + std::string(a);
  }
  throw po::error("--format: unknown format '" + format + "' (expected " + names + ")");
}

void SeriesOptions::add(po::options_description& o, bool with_metric, bool metric_required) {
  o.add_options()("help,h", "show this help")("run", po::value(&run), "run id (default: the newest run)")(
      "dim", po::value(&dim)->default_value(kDefaultDim),
      "homology dimension: 0 (components) or 1 (loops); the default is the API's, proto/api.md")(
      "force", po::value(&force)->default_value("normal"), "normal or tangential force network");
  if (with_metric) {
    auto* value = po::value(&metric);
    if (metric_required) value->required();
    o.add_options()("metric", value, "bottleneck, wasserstein1, wasserstein2 or wasserstein (with --q)")(
        "q", po::value(&q), "the exponent of --metric wasserstein: a real number >= 1")(
        "essential", po::value(&essential)->default_value("floor"), "never-dying classes: floor, sentinel or separate");
  }
}

nlohmann::json SeriesOptions::checked(const po::variables_map& vm) const {
  nlohmann::json p = {{"dim", dim_option(dim)}, {"force", to_string(force_option(force))}};
  if (!run.empty()) p["run"] = run;
  if (vm.count("metric")) {
    const MetricChoice choice = metric_option(metric, vm.count("q") ? std::optional(q) : std::nullopt);
    p["metric"] = choice.name;
    if (vm.count("q")) p["q"] = q;
  }
  if (vm.count("essential")) p["essential"] = to_string(essential_option(essential));
  return p;
}

}  // namespace fnet::client
