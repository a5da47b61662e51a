#include "result_table.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "io/atomic_file.hpp"

namespace topomill::cli {

namespace {
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
std::string md_field(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}
}  // namespace

void ResultTable::write_csv(const std::string& path) const {
  write_atomically(path, [&](std::ostream& out) {
    for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << csv_field(header[i]);
    out << "\n";
    for (const auto& row : rows) {
      for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << csv_field(row[i]);
      out << "\n";
    }
  });
}

std::string ResultTable::markdown() const {
  std::string s = "|";
  for (const auto& h : header) s += " " + md_field(h) + " |";
  s += "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) s += "---|";
  s += "\n";
  for (const auto& row : rows) {
    s += "|";
    for (const auto& c : row) s += " " + md_field(c) + " |";
    s += "\n";
  }
  return s;
}

void ResultTable::write_markdown(const std::string& path) const {
  write_atomically(path, [&](std::ostream& out) { out << markdown(); });
}

std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

double parameter(const CaseResult& r, const std::string& name) {
  const auto it = r.roughness.find(name);
  return r.ok && it != r.roughness.end() ? it->second : std::numeric_limits<double>::quiet_NaN();
}

std::string stage_list(const CaseResult& r) {
  std::string s;
  for (const auto& [name, seconds] : r.stages) {
    if (name == "setup" || name == "output") continue;
    s += (s.empty() ? "" : ", ") + name + " " + cell(seconds) + " s";
  }
  return s;
}

}  // namespace topomill::cli
