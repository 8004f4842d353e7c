#include "distance_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/codec/diagram_json.hpp"
#include "common/codec/frame_csv.hpp"
#include "common/distance/diagonal_flow.hpp"
#include "common/distance/simplex_transport.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"
#include "common/topology/persistence.hpp"

namespace fnet::test {

Diagram random_diagram(std::mt19937_64& rng, std::size_t count, double top, bool grid) {
  std::uniform_real_distribution<double> u(0, 1);
  Diagram d;
  for (std::size_t k = 0; k < count; ++k) {
    if (!d.empty() && u(rng) < 0.1) {
      d.push_back(d[static_cast<std::size_t>(u(rng) * static_cast<double>(d.size()))]);
      continue;
    }
    double b = top * u(rng), de = b * u(rng);
    if (grid) b = std::round(b * 4) / 4, de = std::round(de * 4) / 4;
    if (u(rng) < 0.15) de = kNeverDies;
    if (de != kNeverDies && de > b) std::swap(b, de);
    d.push_back({b, de});
  }
  return d;
}

Diagram perturbed(std::mt19937_64& rng, const Diagram& d, double noise) {
  std::uniform_real_distribution<double> u(-1, 1), v(0, 1);
  Diagram out;
  for (const PersistencePoint& p : d) {
    if (v(rng) < 0.03) continue;
    double b = std::max(0.0, p.birth + noise * u(rng));
    double de = p.death == kNeverDies ? kNeverDies : std::clamp(p.death + noise * u(rng), 0.0, b);
    out.push_back({b, de});
  }
  const std::size_t extra = d.size() / 30 + 1;
  for (std::size_t k = 0; k < extra && !d.empty(); ++k) {
    const PersistencePoint p = d[static_cast<std::size_t>(v(rng) * static_cast<double>(d.size()))];
    if (p.death == kNeverDies) continue;
    const double mid = (p.birth + p.death) / 2;
    out.push_back({mid + noise * v(rng), mid});
  }
  return out;
}

Diagram scaled(const Diagram& d, double c) {
  Diagram out = d;
  for (PersistencePoint& p : out) {
    p.birth *= c;
    if (p.death != kNeverDies) p.death *= c;
  }
  return out;
}

namespace {

struct Pt {
  double x, y;
};

double linf_of(Pt a, Pt b) { return std::max(std::fabs(a.x - b.x), std::fabs(a.y - b.y)); }

// The q-norm of a list of costs (q == 0: the largest), in long double and held as top^q * scaled
// with top the largest cost so far: no ratio to top exceeds 1, so no power overflows for any q,
// and powers that underflow are below 1e-4900 of the total.
struct Norm {
  long double q = 0, top = 0, scaled = 0;

  Norm with(long double cost) const {
    if (q == 0) return {q, std::max(top, cost), 0};
    if (cost == 0) return *this;
    if (cost > top) return {q, cost, scaled * std::pow(top / cost, q) + 1};
    return {q, top, scaled + std::pow(cost / top, q)};
  }
  long double value() const { return q == 0 || top == 0 ? top : top * std::pow(scaled, 1 / q); }
};

}  // namespace

double brute_force_distance(const Diagram& a, const Diagram& b, double q, EssentialConvention convention) {
  // The conventions as README defines them, independently of common/essential_convention.cpp.
  std::vector<Pt> pa, pb;
  std::vector<double> ea, eb;
  for (const auto& [src, pts, ess] : {std::tie(a, pa, ea), std::tie(b, pb, eb)}) {
    for (const PersistencePoint& p : src) {
      if (p.death == -1 && convention == EssentialConvention::separate) {
        ess.push_back(p.birth);
      } else if (p.death == -1 && convention == EssentialConvention::floor) {
        pts.push_back({p.birth, 0});
      } else {
        pts.push_back({p.birth, p.death});
      }
    }
  }
  const double inf = std::numeric_limits<double>::infinity();
  if (ea.size() != eb.size()) return inf;
  // Essential classes: every bijection, not just the sorted one. The optimum splits into the best
  // bijection of these plus the best matching of the rest.
  std::sort(eb.begin(), eb.end());
  const Norm none{q};
  Norm best_ess = none;
  bool first = true;
  do {
    Norm acc = none;
    for (std::size_t k = 0; k < ea.size(); ++k) acc = acc.with(std::fabs(ea[k] - eb[k]));
    if (first || acc.value() < best_ess.value()) best_ess = acc;
    first = false;
  } while (std::next_permutation(eb.begin(), eb.end()));

  std::vector<char> used(pb.size(), 0);
  long double best = inf;
  std::function<void(std::size_t, Norm)> go = [&](std::size_t i, Norm acc) {
    if (acc.value() >= best) return;
    if (i == pa.size()) {
      for (std::size_t j = 0; j < pb.size(); ++j)
        if (!used[j]) acc = acc.with(std::fabs(pb[j].x - pb[j].y) / 2);
      best = std::min(best, acc.value());
      return;
    }
    go(i + 1, acc.with(std::fabs(pa[i].x - pa[i].y) / 2));
    for (std::size_t j = 0; j < pb.size(); ++j) {
      if (used[j]) continue;
      used[j] = 1;
      go(i + 1, acc.with(linf_of(pa[i], pb[j])));
      used[j] = 0;
    }
  };
  go(0, best_ess);
  return static_cast<double>(best);
}

FrameDiagramsPair lammps_diagrams(int frame, bool tangential) {
  char name[64];
  const std::filesystem::path dir = std::filesystem::path(FNET_TEST_DATA) / "lammps-mu0.5-seed777";
  std::snprintf(name, sizeof name, "frame_%04d_contacts.csv", frame);
  const auto contacts = dir / name;
  std::snprintf(name, sizeof name, "frame_%04d_particles.csv", frame);
  const auto particles = dir / name;
  Frame f = read_frame_csv(contacts, particles);
  validate(f);
  const FrameDiagrams d = compute_persistence(build_network(f, tangential ? ForceKind::tangential : ForceKind::normal));
  return {d.pd0, d.pd1};
}

bool oracle_available() {
  const std::string python = FNET_ORACLE_PYTHON;
  if (python.empty() || python.find("NOTFOUND") != std::string::npos) return false;
  const std::string cmd = python + " -c \"import scipy.optimize, scipy.sparse.csgraph\" 2>/dev/null";
  return std::system(cmd.c_str()) == 0;
}

std::vector<double> oracle_distances(const Diagram& a, const Diagram& b, EssentialConvention convention,
                                     const std::vector<std::string>& metrics) {
  TempDir dir;
  const auto fa = dir.path() / "a.json", fb = dir.path() / "b.json";
  std::ofstream(fa) << nlohmann::json{{"pd1", to_json(a)}}.dump();
  std::ofstream(fb) << nlohmann::json{{"pd1", to_json(b)}}.dump();
  std::string cmd = std::string(FNET_ORACLE_PYTHON) + " " + FNET_DISTANCE_ORACLE + " " + fa.string() + " " +
                    fb.string() + " pd1 " + std::string(to_string(convention));
  for (const std::string& m : metrics) cmd += " " + m;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run " + cmd);
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) out += buf.data();
  const nlohmann::json j = nlohmann::json::parse(out);
  std::vector<double> values;
  for (const std::string& m : metrics)
    values.push_back(j.at(m).is_null() ? std::numeric_limits<double>::quiet_NaN() : j.at(m).get<double>());
  return values;
}

namespace {
// Costs as DiagonalFlow takes them (q = 1, 2 in unit 1 without a division), but uncapped: the
// bound below holds with infinite costs too.
double power(double x, double q, double unit) {
  if (unit == 1 && (q == 1 || q == 2)) return q == 1 ? x : x * x;
  return std::pow(x / unit, q);
}
}  // namespace

Certificate certify_wasserstein(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double q,
                                double unit, WassersteinSolver solver) {
  std::vector<double> da, db;
  for (const PlanePoint p : a) da.push_back(power(std::fabs(p.x - p.y) / 2, q, unit));
  for (const PlanePoint p : b) db.push_back(power(std::fabs(p.x - p.y) / 2, q, unit));
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::int64_t> mate_a(n);
  std::vector<double> pi;
  if (solver == WassersteinSolver::network_simplex) {
    FlowState flow(a, b, ArcPower(q, unit));
    PairOracle oracle(flow);
    const DiagonalFlowParams params;
    DualCertificate certificate(params);
    SimplexTransportStats stats;
    solve_by_simplex(flow, oracle, certificate, 1, {}, stats);
    mate_a = flow.mate_a;
    pi = flow.pi;
  } else {
    DiagonalFlow flow(a, b, ArcPower(q, unit));
    flow.solve();
    for (std::uint32_t i = 0; i < n; ++i) mate_a[i] = flow.mate_of_a(i);
    pi.assign(flow.potentials().begin(), flow.potentials().end());
  }
  const double ha = pi[n + m], hb = pi[n + m + 1];
  Certificate cert;
  // The matching, from the mates alone.
  std::vector<int> used(m, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t j = mate_a[i];
    if (j >= 0) {
      cert.matching_valid &= ++used[static_cast<std::size_t>(j)] == 1;
      cert.primal += power(linf_distance(a[i], b[static_cast<std::size_t>(j)]), q, unit);
    } else {
      cert.matching_valid &= j == DiagonalFlow::kDiagonal;
      cert.primal += da[i];
    }
  }
  for (std::size_t j = 0; j < m; ++j)
    if (!used[j]) cert.primal += db[j];
  // The dual bound, every arc scanned.
  double dual = static_cast<double>(n) * hb - static_cast<double>(m) * ha;
  for (std::size_t i = 0; i < n; ++i) dual -= pi[i] + std::max(0.0, -(da[i] + pi[i] - hb));
  for (std::size_t j = 0; j < m; ++j) dual += pi[n + j] - std::max(0.0, -(db[j] + ha - pi[n + j]));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      const double c = power(linf_distance(a[i], b[j]), q, unit);
      if (c < da[i] + db[j]) dual -= std::max(0.0, -(c + pi[i] - pi[n + j]));
    }
  cert.dual = ha >= hb - 1e-12 ? dual : -std::numeric_limits<double>::infinity();
  return cert;
}

}  // namespace fnet::test
