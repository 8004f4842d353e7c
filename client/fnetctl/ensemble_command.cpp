// fnetctl ensembles, and the binned curves of fnetctl query (--ensemble, --bins, --bin-count,
// --axis; --ratio also for a run's own series).
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>

#include "client/fnetctl/commands.hpp"
#include "client/fnetctl/csv_provenance.hpp"
#include "client/fnetctl/value_text.hpp"

namespace po = boost::program_options;

namespace fnet::client {
namespace {

std::string cell(const json& v, int significant) {
  return v.is_null() ? "-" : rounded_number(v.get<double>(), significant);
}

std::string exact_cell(const json& v) { return v.is_null() ? "" : exact_number(v.get<double>()); }

void print_ensembles_table(const json& r) {
  std::printf("%-34s %5s %7s %6s %6s %10s %10s %10s %4s\n", "ensemble", "runs", "frames", "mu", "N", "v_c", "rho_J",
              "+-", "n_J");
  for (const json& e : r["ensembles"]) {
    const json& j = e["rho_j"];
    std::printf("%-34s %5zu %7zu %6s %6s %10s %10s %10s %4zu\n", e["ensemble"].get<std::string>().c_str(),
                e["runs"].size(), e["frames"].get<std::size_t>(), cell(e["friction"], 3).c_str(),
                e["particles"].is_null() ? "-" : e["particles"].dump().c_str(), cell(e["compression_speed"], 3).c_str(),
                cell(j["mean"], 5).c_str(), cell(j["standard_error"], 2).c_str(), j["n"].get<std::size_t>());
  }
}

// One row per ensemble, every number exact; its runs joined by ';'.
void print_ensembles_csv(const json& r) {
  std::cout << "ensemble,runs,frames,friction,particles,compression_speed,rho_j,rho_j_stderr,rho_j_n,last_activity\n";
  for (const json& e : r["ensembles"]) {
    std::string runs;
    for (const json& run : e["runs"]) {
      if (!runs.empty()) runs.push_back(';');
      runs.append(run.get<std::string>());
    }
    std::cout << e["ensemble"].get<std::string>() << "," << runs << "," << e["frames"].get<std::size_t>() << ","
              << exact_cell(e["friction"]) << "," << (e["particles"].is_null() ? "" : e["particles"].dump()) << ","
              << exact_cell(e["compression_speed"]) << "," << exact_cell(e["rho_j"]["mean"]) << ","
              << exact_cell(e["rho_j"]["standard_error"]) << "," << e["rho_j"]["n"].get<std::size_t>() << ","
              << exact_cell(e["last_activity"]) << "\n";
  }
}

bool infinite_at(const json& r, std::size_t k) {
  const json& infinite = r.value("infinite", json());
  return infinite.is_array() && infinite[k].get<bool>();
}

// A bin's mean: the number, inf, or empty ("-" in tables) for an undefined ratio (0/0).
std::string mean_cell(const json& r, std::size_t k, CellStyle style) {
  if (infinite_at(r, k)) return "inf";
  const json& v = r["mean"][k];
  if (v.is_null()) return style == CellStyle::csv ? "" : "-";
  return style == CellStyle::csv ? exact_number(v.get<double>()) : rounded_number(v.get<double>(), 8);
}

void print_curve_csv(const json& r) {
  std::cout << "rho_lo,rho_hi,rho,mean,stderr,n_runs,n,z\n";
  for (std::size_t k = 0; k < r["n"].size(); ++k)
    std::cout << exact_number(r["rho_lo"][k].get<double>()) << "," << exact_number(r["rho_hi"][k].get<double>()) << ","
              << exact_number(r["rho"][k].get<double>()) << "," << mean_cell(r, k, CellStyle::csv) << ","
              << exact_cell(r["stderr"][k]) << "," << r["n_runs"][k].get<std::size_t>() << ","
              << r["n"][k].get<std::size_t>() << "," << exact_number(r["z"][k].get<double>()) << "\n";
}

void print_curve_table(const json& r) {
  const bool shifted = r["axis"] == "rho_minus_rho_j";
  std::cout << (r["ensemble"].is_null() ? "run " + r["run"].get<std::string>()
                                        : "ensemble " + r["ensemble"].get<std::string>())
            << " (" << r["runs"].size() << " run(s)), "
            << (r["ratio"].is_null() ? r["metric"].get<std::string>()
                                     : "d_B / d_W" + r["ratio"].get<std::string>().substr(11) + " (ratio of bin means)")
            << (r["ratio"].is_null() && r.contains("q") && r["metric"] == "wasserstein"
                    ? " q=" + exact_number(r["q"].get<double>())
                    : "")
            << ", PD" << r["dim"].get<int>() << ", " << r["force"].get<std::string>()
            << " forces, essential=" << r["essential"].get<std::string>() << ", "
            << (r.contains("bins") ? std::to_string(r["bins"].get<std::size_t>()) + " bins"
                                   : "bin width " + exact_number(r["bin_width"].get<double>()))
            << " in " << (shifted ? "rho - rho_J" : "rho") << "\n";
  if (shifted && !r["runs_without_rho_j"].empty()) {
    std::cout << "left out (Z never reached 3):";
    for (const json& run : r["runs_without_rho_j"]) std::cout << " " << run.get<std::string>();
    std::cout << "\n";
  }
  // drho: rho - rho_J, named short so that the columns stay apart.
  const std::string x = shifted ? "drho" : "rho";
  if (shifted) std::cout << "drho = rho - rho_J\n";
  std::cout << std::setw(11) << (x + "_lo") << std::setw(11) << (x + "_hi") << std::setw(11) << x << std::setw(16)
            << "mean" << std::setw(12) << "stderr" << std::setw(7) << "n_runs" << std::setw(6) << "n" << std::setw(11)
            << "Z"
            << "\n";
  for (std::size_t k = 0; k < r["n"].size(); ++k)
    std::cout << std::setw(11) << cell(r["rho_lo"][k], 6) << std::setw(11) << cell(r["rho_hi"][k], 6) << std::setw(11)
              << cell(r["rho"][k], 6) << std::setw(16) << mean_cell(r, k, CellStyle::table) << std::setw(12)
              << cell(r["stderr"][k], 3) << std::setw(7) << r["n_runs"][k].get<std::size_t>() << std::setw(6)
              << r["n"][k].get<std::size_t>() << std::setw(11) << cell(r["z"][k], 4) << "\n";
}

}  // namespace

int ensembles_command(RpcClient& rpc, const std::vector<std::string>& args) {
  po::options_description o(
      "usage: fnetctl ensembles [--format table|csv|json]\n\n"
      "The ensembles of realizations the server knows (runs announced with fnet-simd --ensemble), by\n"
      "name: their runs, committed frames, the setting they share (mu, N, v_c; - where the runs\n"
      "differ) and the mean rho_J of the runs that have one, with its standard error.\n\noptions");
  std::string format = "table";
  o.add_options()("help,h", "show this help")(
      "format", po::value(&format)->default_value("table"),
      "table, csv (exact numbers; columns ensemble,runs,frames,friction,particles,compression_speed,"
      "rho_j,rho_j_stderr,rho_j_n,last_activity; runs joined by ';') or json (the API's answer)");
  if (!parse_command(o, args)) return kOk;
  format_option(format, {"table", "csv", "json"});
  const json r = rpc.call("ensembles.list");
  if (format == "json")
    std::cout << r.dump() << "\n";
  else if (format == "csv") {
    std::cout << csv_provenance_line(rpc, "ensembles.list", "none (a list)") << "\n";
    print_ensembles_csv(r);
  } else
    print_ensembles_table(r);
  return kOk;
}

void CurveOptions::add(po::options_description& o) {
  o.add_options()("ensemble", po::value(&ensemble), "bin the series of every run of this ensemble (ensemble.series)")(
      "bins", po::value(&bin_width), "bin width in rho of a binned curve (default 0.002 with --ensemble)")(
      "bin-count", po::value(&bin_count), "instead of --bins: this many bins over the samples' range")(
      "axis", po::value(&axis)->default_value("rho"),
      "x of a binned curve: rho, or rho-minus-rho-j (each run's rho - rho_J; runs whose Z never reached 3 are left "
      "out)")("ratio", po::value(&ratio),
              "wasserstein1 or wasserstein2: the ratio d_B / d_Wq (per frame for a run; for a binned curve the ratio "
              "of the bin means); --metric is then bottleneck or omitted");
}

bool CurveOptions::binned(const po::variables_map& vm) const {
  return vm.count("ensemble") || vm.count("bins") || vm.count("bin-count") || !vm["axis"].defaulted();
}

void CurveOptions::check(const po::variables_map& vm, json& params) const {
  if (vm.count("ratio")) {
    if (ratio != "wasserstein1" && ratio != "wasserstein2")
      throw po::error("--ratio must be wasserstein1 or wasserstein2, got '" + ratio + "'");
    if (vm.count("metric") && params.value("metric", "") != "bottleneck")
      throw po::error("--metric must be bottleneck (or omitted) with --ratio: the ratio is d_B / d_Wq");
    params.erase("metric");
    params["ratio"] = ratio;
  } else if (!vm.count("metric")) {
    throw po::error("the option '--metric' is required but missing (or give --ratio)");
  }
  if (!binned(vm)) return;
  if (vm.count("from") || vm.count("to")) throw po::error("--from and --to select frames of a run's series, not bins");
  if (vm.count("bins") && vm.count("bin-count")) throw po::error("give --bins (a width) or --bin-count, not both");
  if (vm.count("bins")) {
    if (!std::isfinite(bin_width) || bin_width <= 0)
      throw po::error("--bins is a bin width in rho and must be a finite number > 0, got " + exact_number(bin_width));
    params["bin_width"] = bin_width;
  }
  if (vm.count("bin-count")) {
    if (bin_count < 1) throw po::error("--bin-count must be an integer >= 1, got " + std::to_string(bin_count));
    params["bins"] = bin_count;
  }
  if (axis == "rho-minus-rho-j" || axis == "rho_minus_rho_j")
    params["axis"] = "rho_minus_rho_j";
  else if (axis != "rho")
    throw po::error("--axis must be rho or rho-minus-rho-j, got '" + axis + "'");
  if (vm.count("ensemble")) {
    if (vm.count("run")) throw po::error("give --ensemble or --run, not both");
    params["ensemble"] = ensemble;
  } else if (!params.contains("run")) {
    throw po::error("a binned curve needs --ensemble E or --run R");
  }
}

int curve_query(RpcClient& rpc, const json& params, const std::string& format) {
  const json r = rpc.call("ensemble.series", params);
  if (format == "json")
    std::cout << r.dump() << "\n";
  else if (format == "csv") {
    const std::string what = r["ensemble"].is_string() ? "ensemble " + r["ensemble"].get<std::string>()
                                                       : "run " + r["run"].get<std::string>();
    std::cout << csv_provenance_line(rpc,
                                     what + ", " + r["metric"].get<std::string>() +
                                         (r["ratio"].is_string() ? " / " + r["ratio"].get<std::string>() : "") + " PD" +
                                         r["dim"].dump() + ", " + r["force"].get<std::string>() +
                                         " forces, binned in " + r["axis"].get<std::string>() +
                                         "; mean and stderr over the realizations",
                                     r["essential"].get<std::string>())
              << "\n";
    print_curve_csv(r);
  } else
    print_curve_table(r);
  return kOk;
}

}  // namespace fnet::client
