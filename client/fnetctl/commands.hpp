// fnetctl's commands that live in their own files.
#pragma once

#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "client/fnetctl/cli_options.hpp"
#include "client/rpc/rpc_client.hpp"

namespace fnet::client {

int watch_command(const Endpoint& at, const std::vector<std::string>& args);
int blocks_command(const Endpoint& at, const std::vector<std::string>& args);

// fnetctl ensembles.
int ensembles_command(RpcClient& rpc, const std::vector<std::string>& args);

// The options of fnetctl query that ask for a binned curve (ensemble.series) or a ratio.
struct CurveOptions {
  std::string ensemble, axis = "rho", ratio;
  double bin_width = 0;
  long long bin_count = 0;

  void add(boost::program_options::options_description& options);
  // --ensemble, --bins, --bin-count or --axis: the answer is ensemble.series's, not series.get's.
  bool binned(const boost::program_options::variables_map& vm) const;
  // Checks the options (usage errors name the flag) and adds them to series.get's `params`.
  void check(const boost::program_options::variables_map& vm, json& params) const;
};

// ensemble.series with `params`, printed as a table, CSV or the API's JSON.
int curve_query(RpcClient& rpc, const json& params, const std::string& format);

}  // namespace fnet::client
