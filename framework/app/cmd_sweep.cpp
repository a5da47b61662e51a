// topomill sweep SCENE --vary key=v1,v2 [--vary ...]: the cross product of the values, one case
// each, in one table (CSV, Markdown) with the varied keys as columns, and a plot of Sa per key.
#include <cmath>
#include <filesystem>
#include <iostream>

#include "batch_options.hpp"
#include "commands.hpp"
#include "distribution.hpp"
#include "io/png_chart.hpp"
#include "result_table.hpp"

namespace fs = std::filesystem;

namespace topomill::cli {

namespace {

struct Varied {
  std::string key;
  std::vector<std::string> values;
};

// Splits "v1,v2,..." at the commas outside brackets, braces and quotes ("[0.3, 0.3]" is one).
std::vector<std::string> split_values(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  int depth = 0;
  bool quoted = false;
  for (char c : text) {
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == '[' || c == '{')) ++depth;
    if (!quoted && (c == ']' || c == '}')) --depth;
    if (c == ',' && depth == 0 && !quoted) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

Varied parse_vary(const std::string& spec) {
  const auto eq = spec.find('=');
  Varied v;
  if (eq == std::string::npos || eq == 0)
    throw InputError(SourceRef{"command line"}, "--vary",
                     "'" + spec + "': expected table.key=value1,value2,...");
  v.key = spec.substr(0, eq);
  v.values = split_values(spec.substr(eq + 1));
  for (const auto& value : v.values)
    if (value.empty())
      throw InputError(SourceRef{"command line"}, "--vary",
                       "'" + spec + "': an empty value in the list");
  return v;
}

std::vector<Case> cross_product(const std::vector<Varied>& varied) {
  std::vector<Case> cases(1);
  for (const auto& v : varied) {
    std::vector<Case> next;
    for (const auto& c : cases)
      for (const auto& value : v.values) {
        Case n = c;
        n.columns.emplace_back(v.key, value);
        n.overrides.push_back(v.key + "=" + value);
        next.push_back(n);
      }
    cases = next;
  }
  for (auto& c : cases) {
    std::string id;
    for (const auto& [k, value] : c.columns) id += (id.empty() ? "" : "__") + k + "=" + value;
    c.id = case_id(id);
  }
  return cases;
}

double as_number(const std::string& s) {
  try {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    return used == s.size() ? v : NAN;
  } catch (const std::exception&) {
    return NAN;
  }
}

// "table.key (unit)", the unit from the key's schema (the core's or the table's model's).
std::string axis_label(const Scene& scene, const std::string& dotted) {
  const auto dot = dotted.find('.');
  if (dot == std::string::npos) return dotted;
  const std::string table = dotted.substr(0, dot), key = dotted.substr(dot + 1);
  const ParamSpec* spec = nullptr;
  for (const auto& [name, schema] : core_schemas())
    if (name == table) spec = schema.find(key);
  if (!spec)
    for (const auto& [name, st] : scene.slots)
      if (name == table && st.model) spec = st.model->schema.find(key);
  return spec && !spec->unit.empty() ? dotted + " (" + spec->unit + ")" : dotted;
}

// Sa against each varied key; the other keys' combinations are the series. A key with text
// values is plotted against the values' positions.
void plot_per_key(const Scene& scene, const std::vector<Varied>& varied,
                  const std::vector<Case>& cases, const std::vector<CaseResult>& results,
                  const fs::path& dir) {
  for (std::size_t k = 0; k < varied.size(); ++k) {
    std::map<std::string, Series> series;
    for (std::size_t i = 0; i < cases.size() && i < results.size(); ++i) {
      std::string others;
      for (std::size_t m = 0; m < varied.size(); ++m)
        if (m != k)
          others += (others.empty() ? "" : ", ") + cases[i].columns[m].first + "=" +
                    cases[i].columns[m].second;
      Series& s = series[others];
      s.name = others.empty() ? "Sa" : others;
      const std::string& value = cases[i].columns[k].second;
      double x = as_number(value);
      if (!std::isfinite(x)) {
        const auto& vals = varied[k].values;
        x = static_cast<double>(std::find(vals.begin(), vals.end(), value) - vals.begin());
      }
      s.x.push_back(x);
      s.y.push_back(parameter(results[i], "Sa"));
    }
    std::vector<Series> list;
    for (auto& [name, s] : series) list.push_back(s);
    ChartLabels labels;
    labels.title = "Sa against " + varied[k].key;
    labels.x = axis_label(scene, varied[k].key);
    labels.y = "Sa (µm)";
    write_line_chart((dir / ("sweep_" + case_id(varied[k].key) + ".png")).string(), labels, list);
  }
}

}  // namespace

int cmd_sweep(const Args& args) {
  BatchOptions b;
  std::vector<std::string> vary;
  po::options_description opts(
      "topomill sweep SCENE --vary table.key=v1,v2,... [--vary ...] [--jobs N]: runs the cross "
      "product of the values (resumable: a rerun skips finished cases) and writes sweep.csv, "
      "sweep.md and a plot of Sa per varied key.\nUnder mpirun the ranks share the cases");
  opts.add_options()("vary", po::value(&vary)->composing(),
                     "a key and its values, e.g. --vary cutting.feed_per_tooth=0.05,0.1,0.15");
  add_batch_options(opts, b);
  LoadedScene loaded = load_batch(args, opts, b, "sweep");
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  if (vary.empty())
    throw InputError(SourceRef{"command line"}, "--vary", "give at least one key to vary");
  std::vector<Varied> varied;
  for (const auto& spec : vary) {
    varied.push_back(parse_vary(spec));
    for (std::size_t k = 0; k + 1 < varied.size(); ++k)
      if (varied[k].key == varied.back().key)
        throw InputError(SourceRef{"command line"}, "--vary",
                         "'" + varied.back().key +
                             "' is varied twice: expected each key once, with all its values "
                             "in one list (--vary " +
                             varied.back().key + "=v1,v2,...)");
    for (const auto& value : varied.back().values)
      check_variant(b, {varied.back().key + "=" + value}, "--vary " + varied.back().key);
  }
  const std::vector<Case> cases = cross_product(varied);
  const auto lock = lock_batch_output(b, cases);
  const std::vector<CaseResult> results = run_cases(cases, runner_options(b));
  if (Distribution::instance().rank() != 0) return 0;

  ResultTable table;
  table.header = {"case"};
  for (const auto& v : varied) table.header.push_back(v.key);
  for (const char* h : {"status", "Sa_um", "Sq_um", "Sz_um", "Ssk", "Sku", "Sdq", "Sdr_percent",
                        "time_s", "stages", "error"})
    table.header.push_back(h);
  const bool ranks = Distribution::instance().ranks() > 1;
  if (ranks) table.header.push_back("rank");
  int failed = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const CaseResult& r = results[i];
    std::vector<std::string> row = {r.id};
    for (const auto& col : cases[i].columns) row.push_back(col.second);
    row.push_back(r.ok ? "ok" : "failed (exit " + std::to_string(r.exit_code) + ")");
    for (const char* p : {"Sa", "Sq", "Sz", "Ssk", "Sku", "Sdq", "Sdr"})
      row.push_back(cell(parameter(r, p)));
    row.push_back(r.ok ? cell(r.wall_s) : "");
    row.push_back(stage_list(r));
    row.push_back(r.error);
    if (ranks) row.push_back(std::to_string(r.rank));
    table.rows.push_back(row);
    failed += r.ok ? 0 : 1;
  }
  const fs::path dir = b.out_dir;
  table.write_csv((dir / "sweep.csv").string());
  table.write_markdown((dir / "sweep.md").string());
  plot_per_key(*loaded.scene, varied, cases, results, dir);
  std::cout << table.markdown() << "\n"
            << results.size() - failed << " of " << results.size() << " cases ok; "
            << (dir / "sweep.csv").string() << "\n";
  return failed ? 3 : 0;
}

}  // namespace topomill::cli
