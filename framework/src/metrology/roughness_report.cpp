#include "metrology/roughness_report.hpp"

#include <cmath>
#include <sstream>

namespace topomill {

toml::table roughness_table(const ParameterValues& v) {
  toml::table t;
  for (const auto& p : v.reported) {
    toml::table entry{{"value", p.value}, {"unit", p.unit}};
    if (!p.method.empty()) entry.insert("method", p.method);
    t.insert(p.name, std::move(entry));
  }
  for (const auto& [name, why] : v.undefined) t.insert(name, toml::table{{"undefined", why}});
  return t;
}

std::string roughness_text(const ParameterValues& v, const std::string& separator, int digits) {
  std::ostringstream os;
  os.precision(digits);
  // Gwyddion's Sdr beside ours when both are reported.
  double gwyddion = NAN;
  bool sdr = false;
  for (const auto& p : v.reported) {
    if (p.name == "Sdr_gwyddion") gwyddion = p.value;
    sdr = sdr || p.name == "Sdr";
  }
  if (!sdr) gwyddion = NAN;
  bool first = true;
  auto next = [&] {
    if (!first) os << separator;
    first = false;
  };
  for (const auto& p : v.reported) {
    if (p.name == "Sdr_gwyddion" && std::isfinite(gwyddion)) continue;  // beside Sdr, below
    next();
    os << p.name << " " << p.value;
    if (p.unit != "1") os << " " << p.unit;
    if (p.name == "Sdr" && std::isfinite(gwyddion))
      os << " (two triangles per cell; Gwyddion's four: " << gwyddion << " %)";
  }
  for (const auto& u : v.undefined) {
    next();
    os << u.first << " undefined (" << u.second << ")";
  }
  return os.str();
}

std::string first_non_finite(const ParameterValues& v) {
  for (const auto& p : v.reported)
    if (!std::isfinite(p.value)) return p.name;
  return "";
}

}  // namespace topomill
