#include "roughness_report.hpp"

#include <cmath>
#include <sstream>

namespace topomill {

toml::table roughness_table(const Roughness& r) {
  toml::table t;
  for (const auto& p : r.reported()) {
    toml::table entry{{"value", p.value}, {"unit", p.unit}};
    if (!p.method.empty()) entry.insert("method", p.method);
    t.insert(p.name, std::move(entry));
  }
  return t;
}

std::string roughness_text(const Roughness& r, const std::string& separator, int digits) {
  std::ostringstream os;
  os.precision(digits);
  bool first = true;
  for (const auto& p : r.reported()) {
    if (p.name == "Sdr_gwyddion") continue;  // beside Sdr, below
    if (!first) os << separator;
    first = false;
    os << p.name << " " << p.value;
    if (p.unit != "1") os << " " << p.unit;
    if (p.name == "Sdr")
      os << " (two triangles per cell; Gwyddion's four: " << r.Sdr_gwyddion << " %)";
  }
  return os.str();
}

std::string first_non_finite(const Roughness& r) {
  for (const auto& p : r.reported())
    if (!std::isfinite(p.value)) return p.name;
  return "";
}

}  // namespace topomill
