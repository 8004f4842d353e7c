// Ensembles of realizations served by a real fnet-server: ensembles.list, ensemble.series checked
// against the bins computed here from each member run's series.get, the parameter errors, live
// ensemble.bins notifications over DDS, and fnetctl ensembles / query --ensemble. The runs are
// LAMMPS frames analyzed by fnet-analyze (store or publish) with --ensemble.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "client/rpc/rpc_client.hpp"
#include "tests/e2e/line_connection.hpp"
#include "tests/e2e/process.hpp"
#include "tests/e2e/service_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::e2e {
namespace {

namespace fs = std::filesystem;
using client::json;
using client::RpcClient;
using namespace std::chrono_literals;

class Ensemble : public ::testing::Test {
 public:
  ~Ensemble() override {
    if (server_) server_->stop();
  }

  // Analyzes LAMMPS frames `source` offline into the data directory as run `run` of `ensemble`.
  void store(const std::string& run, const std::vector<int>& source, const std::string& ensemble) {
    const fs::path csv = lammps_run(tmp_.path() / ("csv-" + run), source);
    ASSERT_EQ(store_run(csv, run, data(), tmp_.path() / ("store-" + run + ".log"), ensemble), 0)
        << "see " << tmp_.path() / ("store-" + run + ".log");
  }

  // Streams LAMMPS frames `source` over DDS as run `run` of `ensemble`, `rate` frames a second.
  std::unique_ptr<Process> publish(const std::string& run, const std::vector<int>& source, const std::string& ensemble,
                                   double rate) {
    const fs::path csv = lammps_run(tmp_.path() / ("pub-" + run), source);
    return e2e::publish(csv, run, domain_, tmp_.path() / ("publish-" + run + ".log"), rate, 0, 30, ensemble);
  }

  void start_server(int domain) {
    domain_ = domain;
    ServerProcess s = e2e::start_server(data(), domain, tmp_.path() / "server.log");
    server_ = std::move(s.process);
    port_ = s.port;
  }

  // A curve of a metric that is not stored is computed frame by frame on request: seconds in a
  // sanitizer build, hence more than the client's default 30 s.
  json call(const std::string& method, const json& params = json::object()) {
    return RpcClient("127.0.0.1", port_, std::chrono::seconds(180)).call(method, params);
  }

  void wait_for_frames(const std::string& run, std::size_t frames) { e2e::wait_for_frames(port_, run, frames, 300s); }

  Outcome ctl(std::vector<std::string> args) {
    return run_fnetctl(port_, std::move(args), tmp_.path() / ("fnetctl-" + std::to_string(++runs_) + ".err"));
  }

  // Three realizations of ensemble "ens" (ens-c never jams: LAMMPS frames 0-5 keep Z below 3),
  // one of "other", and a run of no ensemble.
  void store_ensembles() {
    store("ens-a", {0, 2, 4, 6, 8, 10}, "ens");
    store("ens-b", {1, 3, 5, 7, 8, 9}, "ens");
    store("ens-c", {0, 1, 2, 3, 4, 5}, "ens");
    store("other-a", {0, 1, 2}, "other");
    store("solo", {3, 4, 5}, "");
  }

  fs::path data() const { return tmp_.path() / "data"; }
  const fs::path& scratch() const { return tmp_.path(); }
  unsigned short port() const { return port_; }

 private:
  testing::TempDir tmp_;
  std::unique_ptr<Process> server_;
  int domain_ = 0, runs_ = 0;
  unsigned short port_ = 0;
};

// One value binned: at x (rho, or rho - rho_J), with Z and the value (inf allowed), of the run
// `run` (its place in the curve's `runs`).
struct Sample {
  double x, z, value;
  std::size_t run;
};

struct Bin {
  double lo, hi, rho, mean, z;
  std::optional<double> stderr_;
  std::size_t n_runs, n;
};

// The bins as proto/api.md defines them, written out independently of the server's code: width
// bins [k w, (k+1) w) at multiples of the width, or `count` bins over [min x, max x] (the last
// closed), a sample in the bin whose edges hold it; per bin each run's mean of its samples
// (frames by index), then the mean over the runs (by name) and the standard error across them.
std::vector<Bin> expected_bins(const std::vector<Sample>& samples, double width, std::size_t count) {
  double lo = samples.front().x, hi = lo;
  for (const Sample& s : samples) lo = std::min(lo, s.x), hi = std::max(hi, s.x);
  const double step = count > 0 ? (hi - lo) / static_cast<double>(count) : width;
  const long long last = static_cast<long long>(count) - 1;
  const auto edge = [&](long long k) {
    return count == 0 ? static_cast<double>(k) * width : k > last ? hi : lo + static_cast<double>(k) * step;
  };
  // Per bin, per run: the sums of x, z, value and the count.
  struct Sums {
    double x = 0, z = 0, value = 0;
    std::size_t n = 0;
  };
  std::map<long long, std::map<std::size_t, Sums>> groups;
  for (const Sample& s : samples) {
    long long k = 0;
    if (count == 0 || step > 0) {
      k = static_cast<long long>(std::floor(count > 0 ? (s.x - lo) / step : s.x / width));
      while (s.x < edge(k) && (count == 0 || k > 0)) --k;
      while (s.x >= edge(k + 1) && (count == 0 || k < last)) ++k;
      if (count > 0) k = std::min(k, last);
    }
    Sums& g = groups[k][s.run];
    g.x += s.x, g.z += s.z, g.value += s.value, ++g.n;
  }
  std::vector<Bin> out;
  for (const auto& [k, runs] : groups) {
    Bin b{};
    b.lo = edge(k);
    b.hi = edge(k + 1);
    b.n_runs = runs.size();
    std::vector<double> means;
    double rho = 0, z = 0, v = 0;
    for (const auto& [run, g] : runs) {
      b.n += g.n;
      const double n = static_cast<double>(g.n);
      rho += g.x / n, z += g.z / n;
      means.push_back(g.value / n);
      v += means.back();
    }
    const double r = static_cast<double>(b.n_runs);
    b.rho = rho / r;
    b.z = z / r;
    b.mean = v / r;
    if (b.n_runs >= 2 && std::isfinite(b.mean)) {
      double sq = 0;
      for (const double m : means) sq += (m - b.mean) * (m - b.mean);
      b.stderr_ = std::sqrt(sq / (r - 1)) / std::sqrt(r);
    }
    out.push_back(b);
  }
  return out;
}

// Each member's series.get as samples: frames with a value, at rho - shift, of the run's place in `runs`.
std::vector<Sample> served_samples(Ensemble& t, const std::vector<std::string>& runs, json params,
                                   const std::map<std::string, double>& shift) {
  std::vector<Sample> out;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::string& run = runs[r];
    params["run"] = run;
    const json s = t.call("series.get", params);
    for (std::size_t k = 0; k < s["frame"].size(); ++k) {
      const bool infinite = s.contains("infinite") && s["infinite"][k].get<bool>();
      if (s["value"][k].is_null() && !infinite) continue;
      out.push_back({s["rho"][k].get<double>() - (shift.count(run) ? shift.at(run) : 0.0), s["z"][k].get<double>(),
                     infinite ? INFINITY : s["value"][k].get<double>(), r});
    }
  }
  return out;
}

// The served bins equal `expected`, number for number.
void expect_bins(const json& served, const std::vector<Bin>& expected) {
  ASSERT_EQ(served["n"].size(), expected.size()) << served.dump();
  for (const char* key : {"rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "z"})
    ASSERT_EQ(served[key].size(), expected.size()) << key;
  bool any_infinite = false;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    SCOPED_TRACE("bin " + std::to_string(k));
    const Bin& e = expected[k];
    EXPECT_EQ(served["rho_lo"][k].get<double>(), e.lo);
    EXPECT_EQ(served["rho_hi"][k].get<double>(), e.hi);
    EXPECT_EQ(served["rho"][k].get<double>(), e.rho);
    EXPECT_EQ(served["z"][k].get<double>(), e.z);
    EXPECT_EQ(served["n"][k].get<std::size_t>(), e.n);
    EXPECT_EQ(served["n_runs"][k].get<std::size_t>(), e.n_runs);
    if (std::isinf(e.mean)) {
      any_infinite = true;
      EXPECT_TRUE(served["mean"][k].is_null());
      ASSERT_TRUE(served.contains("infinite"));
      EXPECT_TRUE(served["infinite"][k].get<bool>());
    } else {
      EXPECT_EQ(served["mean"][k].get<double>(), e.mean);
    }
    if (e.stderr_)
      EXPECT_EQ(served["stderr"][k].get<double>(), *e.stderr_);
    else
      EXPECT_TRUE(served["stderr"][k].is_null());
  }
  EXPECT_EQ(served.contains("infinite"), any_infinite);
}

// The ratio of the bin means, bin by bin (numerator and denominator share their bins).
std::vector<Bin> ratio_of(const std::vector<Bin>& top, const std::vector<Bin>& bottom) {
  std::vector<Bin> out = top;
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].mean = top[k].mean / bottom[k].mean;
    out[k].stderr_.reset();
    out[k].n = std::min(top[k].n, bottom[k].n);
    out[k].n_runs = std::min(top[k].n_runs, bottom[k].n_runs);
  }
  return out;
}

TEST_F(Ensemble, SeriesEqualsTheBinsOfItsMembersSeries) {
  store_ensembles();
  start_server(72);
  const std::vector<std::string> members{"ens-a", "ens-b", "ens-c"};
  std::map<std::string, double> rho_j;
  for (const std::string& run : members) {
    const json r = call("run.get", {{"run", run}});
    if (r["rho_j"].is_number()) rho_j[run] = r["rho_j"].get<double>();
  }
  ASSERT_EQ(rho_j.size(), 2u) << "ens-a and ens-b jam, ens-c does not";
  const std::vector<std::string> jammed{"ens-a", "ens-b"};

  struct Case {
    std::string what;
    json series;  // the series.get params that give the samples (run added)
    json binning;
    bool shifted;
  };
  const std::vector<Case> cases = {
      {"bottleneck pd1, width", {{"metric", "bottleneck"}, {"dim", 1}}, {{"bin_width", 0.05}}, false},
      {"W2 pd0 tangential, count",
       {{"metric", "wasserstein2"}, {"dim", 0}, {"force", "tangential"}},
       {{"bins", 4}},
       false},
      {"bottleneck pd1 against rho - rho_J", {{"metric", "bottleneck"}, {"dim", 1}}, {{"bin_width", 0.03}}, true},
      {"W q=3 pd1 (not stored)", {{"metric", "wasserstein"}, {"q", 3}, {"dim", 1}}, {{"bin_width", 0.05}}, false},
      {"sentinel, count, against rho - rho_J",
       {{"metric", "wasserstein1"}, {"dim", 0}, {"essential", "sentinel"}},
       {{"bins", 3}},
       true},
      {"separate: infinite bins",
       {{"metric", "bottleneck"}, {"dim", 0}, {"essential", "separate"}},
       {{"bin_width", 0.1}},
       false},
  };
  std::size_t pooled_differs = 0;  // bins where the mean over runs is not the mean over frames
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    json params = c.series;
    params.update(c.binning);
    params["ensemble"] = "ens";
    if (c.shifted) params["axis"] = "rho_minus_rho_j";
    const json served = call("ensemble.series", params);
    const std::vector<std::string>& used = c.shifted ? jammed : members;
    EXPECT_EQ(served["runs"], json(used));
    EXPECT_EQ(served["ensemble"], "ens");
    EXPECT_TRUE(served["run"].is_null());
    EXPECT_EQ(served["axis"], c.shifted ? "rho_minus_rho_j" : "rho");
    if (c.shifted)
      EXPECT_EQ(served["runs_without_rho_j"], json({"ens-c"}));
    else
      EXPECT_FALSE(served.contains("runs_without_rho_j"));
    const double width = c.binning.value("bin_width", 0.0);
    const std::size_t count = c.binning.value("bins", std::size_t{0});
    const std::vector<Bin> expected = expected_bins(
        served_samples(*this, used, c.series, c.shifted ? rho_j : std::map<std::string, double>{}), width, count);
    expect_bins(served, expected);
    for (const Bin& b : expected) pooled_differs += b.n_runs >= 2 && b.n > b.n_runs;
  }
  EXPECT_GE(pooled_differs, 5u) << "too few bins where several runs have several frames";

  // The ratio curve: the ratio of the bin means of d_B and d_W2, as the paper plots it.
  const json ratio =
      call("ensemble.series", {{"ensemble", "ens"}, {"ratio", "wasserstein2"}, {"dim", 1}, {"bin_width", 0.05}});
  EXPECT_EQ(ratio["ratio"], "wasserstein2");
  EXPECT_EQ(ratio["metric"], "bottleneck");
  expect_bins(
      ratio,
      ratio_of(expected_bins(served_samples(*this, members, {{"metric", "bottleneck"}, {"dim", 1}}, {}), 0.05, 0),
               expected_bins(served_samples(*this, members, {{"metric", "wasserstein2"}, {"dim", 1}}, {}), 0.05, 0)));

  // One run's curve.
  const json one = call("ensemble.series", {{"run", "solo"}, {"metric", "bottleneck"}, {"bins", 2}});
  EXPECT_TRUE(one["ensemble"].is_null());
  EXPECT_EQ(one["run"], "solo");
  EXPECT_EQ(one["runs"], json({"solo"}));
  expect_bins(one, expected_bins(served_samples(*this, {"solo"}, {{"metric", "bottleneck"}}, {}), 0, 2));

  // series.get's ratio: d_B / d_W1 frame by frame.
  const json per_frame = call("series.get", {{"run", "ens-a"}, {"ratio", "wasserstein1"}, {"dim", 1}});
  const json db = call("series.get", {{"run", "ens-a"}, {"metric", "bottleneck"}, {"dim", 1}});
  const json dw = call("series.get", {{"run", "ens-a"}, {"metric", "wasserstein1"}, {"dim", 1}});
  EXPECT_EQ(per_frame["ratio"], "wasserstein1");
  ASSERT_EQ(per_frame["value"].size(), db["value"].size());
  EXPECT_EQ(per_frame["frame"], db["frame"]);
  EXPECT_TRUE(per_frame["value"][0].is_null());
  for (std::size_t k = 1; k < db["value"].size(); ++k)
    EXPECT_EQ(per_frame["value"][k].get<double>(), db["value"][k].get<double>() / dw["value"][k].get<double>()) << k;
}

TEST_F(Ensemble, ListGroupsTheRunsByTheEnsembleTheyAnnounced) {
  store_ensembles();
  start_server(73);
  const json listed = call("ensembles.list");
  ASSERT_EQ(listed["ensembles"].size(), 2u) << listed.dump();
  const json& ens = listed["ensembles"][0];
  EXPECT_EQ(ens["ensemble"], "ens");
  EXPECT_EQ(ens["runs"], json({"ens-a", "ens-b", "ens-c"}));
  EXPECT_EQ(ens["frames"], 18);
  EXPECT_EQ(ens["particles"], 2000);
  const json a = call("run.get", {{"run", "ens-a"}}), b = call("run.get", {{"run", "ens-b"}});
  const double ja = a["rho_j"], jb = b["rho_j"], mean = (ja + jb) / 2;
  EXPECT_EQ(ens["rho_j"]["n"], 2);
  EXPECT_EQ(ens["rho_j"]["mean"].get<double>(), mean);
  EXPECT_DOUBLE_EQ(ens["rho_j"]["standard_error"].get<double>(), std::abs(ja - jb) / 2);
  EXPECT_TRUE(ens["last_activity"].is_number());
  EXPECT_EQ(listed["ensembles"][1]["ensemble"], "other");
  EXPECT_EQ(listed["ensembles"][1]["runs"], json({"other-a"}));
  EXPECT_EQ(listed["ensembles"][1]["rho_j"]["n"], 0);
  EXPECT_TRUE(listed["ensembles"][1]["rho_j"]["mean"].is_null());
}

TEST_F(Ensemble, BadParametersAreNamedBeforeAnyWork) {
  store_ensembles();
  start_server(74);
  LineConnection c(port());
  const auto invalid = [&](const std::string& method, const json& params, const std::string& parameter) {
    const json reply = c.call(method, params);
    SCOPED_TRACE(method + " " + params.dump() + ": " + reply.dump());
    ASSERT_TRUE(reply.contains("error"));
    EXPECT_EQ(reply["error"]["code"], -32602);
    EXPECT_EQ(reply["error"]["data"]["parameter"], parameter);
    EXPECT_NE(reply["error"]["message"].get<std::string>().find("'" + parameter + "'"), std::string::npos);
  };
  for (const char* method : {"ensemble.series", "ensemble.subscribe"}) {
    const json ok = {{"ensemble", "ens"}, {"metric", "bottleneck"}};
    const auto with = [&](const json& change) {
      json p = ok;
      p.update(change);
      return p;
    };
    invalid(method, {{"metric", "bottleneck"}}, "ensemble");
    invalid(method, with({{"run", "ens-a"}}), "ensemble");
    invalid(method, with({{"bin_width", 0}}), "bin_width");
    invalid(method, with({{"bin_width", -0.01}}), "bin_width");
    invalid(method, with({{"bin_width", "0.01"}}), "bin_width");
    invalid(method, with({{"bins", 0}}), "bins");
    invalid(method, with({{"bins", 2.5}}), "bins");
    invalid(method, with({{"bins", 3}, {"bin_width", 0.01}}), "bin_width");
    invalid(method, with({{"axis", "z"}}), "axis");
    invalid(method, with({{"ratio", "wasserstein3"}}), "ratio");
    invalid(method, with({{"ratio", "wasserstein2"}, {"metric", "wasserstein2"}}), "metric");
    invalid(method, with({{"metric", "manhattan"}}), "metric");
    invalid(method, with({{"dim", 2}}), "dim");
    invalid(method, with({{"no_such", 1}}), "no_such");
    // The parameters are checked before the ensemble is looked up.
    invalid(method, {{"ensemble", "nope"}, {"metric", "bottleneck"}, {"bins", 0}}, "bins");
    const json unknown = c.call(method, with({{"ensemble", "nope"}}));
    EXPECT_EQ(unknown["error"]["code"], -32006) << unknown;
    EXPECT_EQ(unknown["error"]["data"]["ensemble"], "nope") << unknown;
    EXPECT_NE(unknown["error"]["message"].get<std::string>().find("'nope'"), std::string::npos) << unknown;
    const json run = c.call(method, {{"run", "nope"}, {"metric", "bottleneck"}});
    EXPECT_EQ(run["error"]["code"], -32001) << run;
    // A run of no ensemble is no ensemble.
    EXPECT_EQ(c.call(method, with({{"ensemble", "solo"}}))["error"]["code"], -32006);
  }
  invalid("series.get", {{"run", "ens-a"}, {"ratio", "wasserstein2"}, {"metric", "wasserstein1"}}, "metric");
  invalid("series.get", {{"run", "ens-a"}, {"ratio", "bottleneck"}}, "ratio");
  invalid("ensemble.unsubscribe", {{"subscription", 12345}}, "subscription");
}

// Applies an ensemble.bins notification to `curve` (an ensemble.series answer): its bins replace
// those of the same rho_lo or are added, those of `removed` go, and the members are the latest.
void apply(json& curve, const json& update) {
  std::map<double, json> bins;
  const auto keys = {"rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z", "infinite"};
  const auto take = [&](const json& from) {
    for (std::size_t k = 0; k < from["rho_lo"].size(); ++k) {
      json bin;
      for (const char* key : keys)
        if (from.contains(key)) bin[key] = from[key][k];
      bins[from["rho_lo"][k].get<double>()] = bin;
    }
  };
  take(curve);
  for (const json& lo : update.value("removed", json::array())) bins.erase(lo.get<double>());
  take(update);
  json out = curve;
  for (const char* key : keys) out[key] = json::array();
  bool any_infinite = false;
  for (const auto& [lo, bin] : bins) {
    for (const char* key : keys)
      if (std::string(key) != "infinite") out[key].push_back(bin[key]);
    const bool inf = bin.contains("infinite") && bin["infinite"].get<bool>();
    out["infinite"].push_back(inf);
    any_infinite |= inf;
  }
  if (!any_infinite) out.erase("infinite");
  out["runs"] = update["runs"];
  curve = out;
}

TEST_F(Ensemble, SubscribersGetTheChangedBinsOfRunsThatJoinLaterUntilTheyLeave) {
  start_server(71);
  // The first realization is under way when the subscriber arrives; the second starts after.
  auto first = publish("live-1", {0, 1, 2, 3, 4, 5, 6, 7}, "live", 4);
  wait_for_frames("live-1", 2);
  auto connection = std::make_unique<LineConnection>(port());
  LineConnection& c = *connection;
  const std::vector<json> requests = {
      {{"ensemble", "live"}, {"metric", "wasserstein"}, {"q", 3}, {"dim", 1}, {"bin_width", 0.02}},
      {{"ensemble", "live"}, {"metric", "bottleneck"}, {"bins", 3}},
  };
  std::vector<json> curves;
  std::vector<std::uint64_t> ids;
  for (const json& r : requests) {
    const json reply = c.call("ensemble.subscribe", r);
    ASSERT_TRUE(reply.contains("result")) << reply;
    ids.push_back(reply["result"]["subscription"].get<std::uint64_t>());
    json curve = reply["result"];
    curve.erase("subscription");
    curves.push_back(curve);
  }
  auto second = publish("live-2", {1, 3, 5, 7, 9}, "live", 4);
  EXPECT_EQ(first->wait(120s), 0);
  EXPECT_EQ(second->wait(120s), 0);
  wait_for_frames("live-1", 8);
  wait_for_frames("live-2", 5);
  // The last notifications follow the last commit closely; a fresh curve then equals the
  // subscriber's, updated notification by notification in order.
  std::vector<json> fresh;
  for (const json& r : requests) fresh.push_back(call("ensemble.series", r));
  std::vector<json> got(requests.size());
  const auto settled = [&] {
    for (std::size_t s = 0; s < requests.size(); ++s) {
      json curve = curves[s];
      for (const json& n : c.notifications)
        if (n["method"] == "ensemble.bins" && n["params"]["subscription"] == ids[s]) apply(curve, n["params"]);
      got[s] = curve;
      if (curve != fresh[s]) return false;
    }
    return true;
  };
  for (int k = 0; k < 100 && !settled(); ++k)
    if (const auto n = c.next(100ms)) c.notifications.push_back(*n);
  for (std::size_t s = 0; s < requests.size(); ++s) {
    EXPECT_EQ(got[s], fresh[s]) << requests[s].dump();
    EXPECT_EQ(fresh[s]["runs"], json({"live-1", "live-2"}));
  }
  const auto notified = [&](std::uint64_t id) {
    return std::count_if(c.notifications.begin(), c.notifications.end(), [&](const json& n) {
      return n["method"] == "ensemble.bins" && n["params"]["subscription"] == id;
    });
  };
  EXPECT_GE(notified(ids[0]), 2);
  EXPECT_GE(notified(ids[1]), 2);
  // The count binning's edges move as the range grows: old bins are removed.
  EXPECT_TRUE(std::any_of(c.notifications.begin(), c.notifications.end(),
                          [](const json& n) { return n["params"].contains("removed"); }));

  // After unsubscribing, a third realization brings no notification of that subscription.
  EXPECT_EQ(c.call("ensemble.unsubscribe", {{"subscription", ids[0]}})["result"]["unsubscribed"], ids[0]);
  const auto before = notified(ids[0]);
  auto third = publish("live-3", {2, 4, 6}, "live", 0);
  EXPECT_EQ(third->wait(120s), 0);
  wait_for_frames("live-3", 3);
  while (const auto n = c.next(1500ms)) c.notifications.push_back(*n);
  EXPECT_EQ(notified(ids[0]), before);
  EXPECT_GT(std::count_if(c.notifications.begin(), c.notifications.end(),
                          [&](const json& n) { return n["params"]["runs"].size() == 3; }),
            0)
      << "the subscription still held saw the third run join";

  // Closing the connection releases the subscription still held.
  EXPECT_EQ(call("server.status")["subscriptions"], 1);
  connection.reset();
  int held = 1;
  for (int k = 0; k < 100 && held != 0; ++k) {
    held = call("server.status")["subscriptions"].get<int>();
    if (held) std::this_thread::sleep_for(50ms);
  }
  EXPECT_EQ(held, 0);
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    if (rows.empty() && line[0] == '#') {  // fnetctl's provenance comment: the builds and the request
      EXPECT_EQ(line.rfind("# fnet-server ", 0), 0u) << line;
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream cs(line);
    for (std::string cell; std::getline(cs, cell, ',');) cells.push_back(cell);
    if (line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A CSV cell against a served number: the same bits, or empty for null.
void expect_cell(const std::string& cell, const json& served) {
  if (served.is_null())
    EXPECT_EQ(cell, "");
  else
    EXPECT_TRUE(same_bits(std::stod(cell), served.get<double>())) << cell << " vs " << served;
}

TEST_F(Ensemble, FnetctlPrintsTheServedEnsemblesAndCurves) {
  store_ensembles();
  start_server(75);
  // ensembles: JSON is the API's answer; CSV carries its numbers exactly.
  Outcome o = ctl({"ensembles", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const json listed = call("ensembles.list");
  EXPECT_EQ(json::parse(o.out), listed);
  o = ctl({"ensembles", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  auto rows = parse_csv(o.out);
  ASSERT_EQ(rows.size(), 3u) << o.out;
  EXPECT_EQ(rows[0],
            (std::vector<std::string>{"ensemble", "runs", "frames", "friction", "particles", "compression_speed",
                                      "rho_j", "rho_j_stderr", "rho_j_n", "last_activity"}));
  EXPECT_EQ(rows[1][0], "ens");
  EXPECT_EQ(rows[1][1], "ens-a;ens-b;ens-c");
  EXPECT_EQ(rows[1][2], "18");
  expect_cell(rows[1][6], listed["ensembles"][0]["rho_j"]["mean"]);
  expect_cell(rows[1][7], listed["ensembles"][0]["rho_j"]["standard_error"]);
  expect_cell(rows[1][9], listed["ensembles"][0]["last_activity"]);
  expect_cell(rows[2][7], listed["ensembles"][1]["rho_j"]["standard_error"]);
  o = ctl({"ensembles"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("other"), std::string::npos) << o.out;

  // query --ensemble: the curve's bins, CSV exact, --bins a width, --bin-count a count.
  const std::vector<std::pair<std::vector<std::string>, json>> queries = {
      {{"--metric", "bottleneck", "--dim", "1", "--bins", "0.05"},
       {{"metric", "bottleneck"}, {"dim", 1}, {"bin_width", 0.05}}},
      {{"--metric", "wasserstein2", "--bin-count", "3", "--axis", "rho-minus-rho-j"},
       {{"metric", "wasserstein2"}, {"bins", 3}, {"axis", "rho_minus_rho_j"}}},
      {{"--ratio", "wasserstein2", "--dim", "1"}, {{"ratio", "wasserstein2"}, {"dim", 1}}},
  };
  for (const auto& [flags, params] : queries) {
    SCOPED_TRACE(params.dump());
    std::vector<std::string> args{"query", "--ensemble", "ens"};
    args.insert(args.end(), flags.begin(), flags.end());
    json p = params;
    p["ensemble"] = "ens";
    const json served = call("ensemble.series", p);
    std::vector<std::string> as_json = args;
    as_json.insert(as_json.end(), {"--format", "json"});
    o = ctl(as_json);
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_EQ(json::parse(o.out), served);
    std::vector<std::string> as_csv = args;
    as_csv.insert(as_csv.end(), {"--format", "csv"});
    o = ctl(as_csv);
    ASSERT_EQ(o.code, 0) << o.err;
    rows = parse_csv(o.out);
    ASSERT_EQ(rows.size(), 1 + served["n"].size()) << o.out;
    EXPECT_EQ(rows[0], (std::vector<std::string>{"rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z"}));
    for (std::size_t k = 0; k < served["n"].size(); ++k) {
      ASSERT_EQ(rows[k + 1].size(), 8u) << o.out;
      expect_cell(rows[k + 1][0], served["rho_lo"][k]);
      expect_cell(rows[k + 1][1], served["rho_hi"][k]);
      expect_cell(rows[k + 1][2], served["rho"][k]);
      expect_cell(rows[k + 1][3], served["mean"][k]);
      expect_cell(rows[k + 1][4], served["stderr"][k]);
      EXPECT_EQ(rows[k + 1][5], served["n_runs"][k].dump());
      EXPECT_EQ(rows[k + 1][6], served["n"][k].dump());
      expect_cell(rows[k + 1][7], served["z"][k]);
    }
    o = ctl(args);
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_NE(o.out.find("ensemble ens"), std::string::npos) << o.out;
    EXPECT_NE(o.out.find(" n_runs "), std::string::npos) << o.out;
  }

  // A run's own ratio series, frame by frame.
  o = ctl({"query", "--run", "ens-a", "--ratio", "wasserstein1", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const json ratio = call("series.get", {{"run", "ens-a"}, {"ratio", "wasserstein1"}});
  rows = parse_csv(o.out);
  ASSERT_EQ(rows.size(), 1 + ratio["frame"].size());
  ASSERT_EQ(rows[0].back(), "value");
  for (std::size_t k = 0; k < ratio["frame"].size(); ++k) expect_cell(rows[k + 1].back(), ratio["value"][k]);

  // Usage errors name the flag; an unknown ensemble is exit 4.
  for (const auto& [args, flag] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"query", "--ensemble", "ens", "--metric", "bottleneck", "--bins", "0"}, "--bins"},
           {{"query", "--ensemble", "ens", "--metric", "bottleneck", "--bins", "0.1", "--bin-count", "2"},
            "--bin-count"},
           {{"query", "--ensemble", "ens", "--metric", "bottleneck", "--bin-count", "0"}, "--bin-count"},
           {{"query", "--ensemble", "ens", "--metric", "bottleneck", "--axis", "z"}, "--axis"},
           {{"query", "--ensemble", "ens", "--ratio", "wasserstein3"}, "--ratio"},
           {{"query", "--ensemble", "ens", "--ratio", "wasserstein2", "--metric", "wasserstein2"}, "--metric"},
           {{"query", "--ensemble", "ens"}, "--metric"},
           {{"query", "--ensemble", "ens", "--metric", "bottleneck", "--from", "1"}, "--from"},
           {{"ensembles", "--format", "xml"}, "--format"},
       }) {
    o = ctl(args);
    EXPECT_EQ(o.code, 2) << ::testing::PrintToString(args) << o.err;
    EXPECT_NE(o.err.find(flag), std::string::npos) << o.err;
    EXPECT_EQ(o.out, "");
  }
  o = ctl({"query", "--ensemble", "nope", "--metric", "bottleneck"});
  EXPECT_EQ(o.code, 4) << o.err;
  EXPECT_NE(o.err.find("nope"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace fnet::e2e
