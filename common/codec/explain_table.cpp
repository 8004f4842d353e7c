#include "common/codec/explain_table.hpp"

#include <cstdio>
#include <sstream>
#include <vector>

namespace fnet {
namespace {

std::string number(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", x);
  return s;
}

std::string point_text(const nlohmann::json& p) {
  if (p.is_null()) return "diagonal";
  std::ostringstream out;
  out << "(" << number(p.at("birth").get<double>()) << ", " << number(p.at("death").get<double>()) << ")";
  return out.str();
}

// "12-40" for a contact, "12-40-41" for a triangle, "-" for none.
std::string simplex_text(const nlohmann::json& s) {
  if (s.is_null()) return "-";
  std::ostringstream out;
  const char* separator = "";
  for (const auto& g : s.at("grains")) out << separator << g.get<std::uint32_t>(), separator = "-";
  return out.str();
}

std::string grains_text(const nlohmann::json& p) {
  if (p.is_null()) return "-";
  return simplex_text(p.at("birth_simplex")) + " / " + simplex_text(p.at("death_simplex"));
}

// "(x, y)", or "(x, y, z)" in a 3D frame: the centre of the grains that create a point's feature;
// empty without positions.
std::string centre_text(const nlohmann::json& p) {
  if (p.is_null() || !p.at("birth_simplex").contains("positions")) return "";
  const auto& positions = p.at("birth_simplex").at("positions");
  if (positions.empty()) return "";
  std::vector<double> sum(positions.at(0).size(), 0.0);
  for (const auto& at : positions)
    for (std::size_t axis = 0; axis < sum.size(); ++axis) sum[axis] += at.at(axis).get<double>();
  const double n = static_cast<double>(positions.size());
  std::ostringstream out;
  const char* separator = "(";
  for (const double s : sum) out << separator << number(s / n), separator = ", ";
  out << ")";
  return out.str();
}

// Whether an answer's positions carry z: its frames are 3D.
bool has_z(const nlohmann::json& answer) {
  for (const auto& t : answer.at("explain"))
    for (const char* side : {"a", "b"})
      if (!t.at(side).is_null() && t.at(side).at("birth_simplex").contains("positions"))
        for (const auto& at : t.at(side).at("birth_simplex").at("positions")) return at.size() == 3;
  return false;
}

}  // namespace

std::string explain_where(const nlohmann::json& term) {
  const std::string a = centre_text(term.at("a")), b = centre_text(term.at("b"));
  if (a.empty() && b.empty()) return "-";
  if (a.empty()) return "b " + b;
  if (b.empty()) return "a " + a;
  if (a == b) return "a = b " + a;
  return "a " + a + " b " + b;
}

void write_explain_table(std::ostream& out, const nlohmann::json& answer, const std::string& metric_label) {
  out << metric_label << " PD" << answer.at("dim").get<int>() << " " << answer.at("force").get<std::string>() << " ("
      << answer.at("essential").get<std::string>()
      << "): " << (answer.at("value").is_null() ? std::string("inf") : number(answer.at("value").get<double>()))
      << "\n";
  if (answer.contains("reason")) out << answer.at("reason").get<std::string>() << "\n";
  if (answer.at("explain").empty()) {
    out << "no term of positive cost\n";
    return;
  }
  out << "a: the first frame's point, b: the second's; where: the centre of the grains that create each "
         "point's feature, in d (one position when both agree)\n";
  char line[400];
  std::snprintf(line, sizeof line, "%4s %12s %26s %26s  %-24s %-24s %s\n", "rank", "cost", "a (birth, death)",
                "b (birth, death)", "a grains: birth / death", "b grains: birth / death",
                has_z(answer) ? "where (x, y, z)" : "where (x, y)");
  out << line;
  for (const auto& t : answer.at("explain")) {
    std::snprintf(line, sizeof line, "%4d %12s %26s %26s  %-24s %-24s %s\n", t.at("rank").get<int>(),
                  number(t.at("cost").get<double>()).c_str(), point_text(t.at("a")).c_str(),
                  point_text(t.at("b")).c_str(), grains_text(t.at("a")).c_str(), grains_text(t.at("b")).c_str(),
                  explain_where(t).c_str());
    out << line;
  }
}

}  // namespace fnet
