// topomill study SCENE [--evaluator NAME ...] [--spacing s1,s2,...] [--knob NAME.key=v1,v2]:
// what accuracy costs in time. The scene runs at a ladder of grid spacings (and of an
// evaluator's own knobs) for each evaluator; each run's Sa, Sq, Sz, its difference from the most
// accurate run (the reference evaluator's finest), wall time, nodes and work counts go into one
// table, and a log-log plot shows the Sa error against the time, one curve per evaluator.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "batch_options.hpp"
#include "commands.hpp"
#include "distribution.hpp"
#include "io/png_chart.hpp"
#include "result_table.hpp"

namespace fs = std::filesystem;

namespace topomill::cli {

namespace {

std::vector<double> parse_spacings(const std::string& text) {
  std::vector<double> out;
  // Every item, the empty ones too ("" and "0.02," are refused, not a default ladder).
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !(v > 0) || !std::isfinite(v)) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      throw InputError(SourceRef{"command line"}, "--spacing",
                       "'" + item + "' is not a positive spacing in mm (e.g. 0.02,0.01,0.005)");
    }
    if (comma == text.size()) break;
    start = comma + 1;
  }
  return out;
}

struct Knob {
  std::string evaluator, key;
  std::vector<std::string> values;
};

Knob parse_knob(const std::string& spec) {
  const auto dot = spec.find('.'), eq = spec.find('=');
  if (dot == std::string::npos || eq == std::string::npos || eq < dot)
    throw InputError(
        SourceRef{"command line"}, "--knob",
        "'" + spec + "': expected EVALUATOR.key=v1,v2 (e.g. zmap.time_step_fraction=0.9,0.45)");
  Knob k{spec.substr(0, dot), spec.substr(dot + 1, eq - dot - 1), {}};
  const std::string list = spec.substr(eq + 1);
  std::size_t start = 0;
  for (;;) {  // every item, the empty ones too: "key=" used to drop the evaluator's cases
    const std::size_t comma = std::min(list.find(',', start), list.size());
    k.values.push_back(list.substr(start, comma - start));
    if (k.values.back().empty())
      throw InputError(SourceRef{"command line"}, "--knob",
                       "'" + spec + "': an empty value in the list: expected v1,v2,...");
    if (comma == list.size()) break;
    start = comma + 1;
  }
  return k;
}

std::string spacing_text(double s) {
  std::ostringstream os;
  os << s;
  return os.str();
}

double stage(const CaseResult& r, const std::string& name) {
  for (const auto& [n, s] : r.stages)
    if (n == name) return s;
  return NAN;
}

// The study's cases: each evaluator at each spacing, coarse to fine, under each setting of its
// knobs (their cross product), with the evaluator and spacing of each.
struct StudyCases {
  std::vector<Case> cases;
  std::vector<std::string> evaluator;
  std::vector<double> spacing;
};

StudyCases study_cases(const BatchOptions& b, const std::vector<std::string>& evaluators,
                       const std::vector<double>& spacings, const std::vector<Knob>& knobs) {
  StudyCases out;
  for (const auto& e : evaluators) {
    check_variant(b, {"evaluator.plugin=\"" + e + "\""}, "--evaluator " + e);
    // The knob settings of this evaluator: their cross product (one empty setting if none).
    std::vector<std::vector<std::pair<std::string, std::string>>> settings(1);
    for (const auto& k : knobs) {
      if (k.evaluator != e) continue;
      std::vector<std::vector<std::pair<std::string, std::string>>> next;
      for (const auto& s : settings)
        for (const auto& v : k.values) {
          auto n = s;
          n.emplace_back(k.key, v);
          next.push_back(n);
        }
      settings = next;
    }
    for (const auto& setting : settings)
      for (double s : spacings) {
        Case c;
        c.overrides = {"evaluator.plugin=\"" + e + "\"", "region.spacing=" + spacing_text(s)};
        std::string knob_text;
        for (const auto& [k, v] : setting) {
          c.overrides.push_back("evaluator." + k + "=" + v);
          knob_text += (knob_text.empty() ? "" : " ") + k + "=" + v;
        }
        c.id = case_id(e + "__spacing=" + spacing_text(s) +
                       (knob_text.empty() ? "" : "__" + knob_text));
        c.columns = {{"evaluator", e}, {"spacing_mm", spacing_text(s)}, {"knobs", knob_text}};
        check_variant(b, c.overrides, "--knob");
        out.cases.push_back(c);
        out.evaluator.push_back(e);
        out.spacing.push_back(s);
      }
  }
  return out;
}

// The reference: the reference evaluator's finest run that succeeded, preferring one without
// knobs; results.size() if none.
std::size_t reference_of(const StudyCases& sc, const std::vector<CaseResult>& results,
                         const std::string& reference) {
  std::size_t ref_index = results.size();
  for (const bool plain : {true, false}) {
    for (std::size_t i = 0; i < results.size(); ++i)
      if (sc.evaluator[i] == reference && results[i].ok &&
          (!plain || sc.cases[i].columns[2].second.empty()) &&
          (ref_index == results.size() || sc.spacing[i] < sc.spacing[ref_index]))
        ref_index = i;
    if (ref_index != results.size()) break;
  }
  return ref_index;
}

// study.csv and study.md: one row per case; and the curves of the Sa error against the evaluate
// time, one per evaluator and knob setting (the reference, with no error, left out). The number
// of failed cases.
int study_table(const StudyCases& sc, const std::vector<CaseResult>& results, const CaseResult* ref,
                ResultTable& table, std::map<std::string, Series>& curves) {
  const double sa_ref = ref ? parameter(*ref, "Sa") : NAN;
  table.header = {"evaluator",   "spacing_mm", "knobs",      "status", "Sa_um", "Sq_um", "Sz_um",
                  "dSa_percent", "time_s",     "evaluate_s", "nodes",  "work",  "error"};
  int failed = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const CaseResult& r = results[i];
    const auto& columns = sc.cases[i].columns;
    const double sa = parameter(r, "Sa");
    const double d = 100 * (sa - sa_ref) / sa_ref;
    std::string work;
    for (const auto& [k, v] : r.work)
      if (k != "grid_nodes" && k != "nodes")
        work += (work.empty() ? "" : " ") + k + "=" + std::to_string(v);
    const auto nodes = r.work.count("grid_nodes") ? r.work.at("grid_nodes") : 0;
    table.rows.push_back({columns[0].second, columns[1].second, columns[2].second,
                          r.ok ? (&r == ref ? "reference" : "ok")
                               : "failed (exit " + std::to_string(r.exit_code) + ")",
                          cell(sa), cell(parameter(r, "Sq")), cell(parameter(r, "Sz")),
                          &r == ref ? "0" : cell(d), r.ok ? cell(r.wall_s) : "",
                          cell(stage(r, "evaluate")), r.ok ? std::to_string(nodes) : "", work,
                          r.error});
    failed += r.ok ? 0 : 1;
    if (&r == ref || !r.ok) continue;
    const std::string name =
        columns[0].second + (columns[2].second.empty() ? "" : " " + columns[2].second);
    Series& s = curves[name];
    s.name = name;
    s.x.push_back(stage(r, "evaluate"));
    s.y.push_back(std::abs(d));
  }
  return failed;
}

}  // namespace

int cmd_study(const Args& args) {
  BatchOptions b;
  std::vector<std::string> evaluators, knobs;
  std::string spacings_text, reference;
  po::options_description opts(
      "topomill study SCENE [--evaluator NAME ...] [--spacing s1,s2,...]: runs the scene at a "
      "ladder of resolutions for each evaluator and writes study.csv, study.md and study.png "
      "(Sa error against time, log-log); resumable");
  opts.add_options()("evaluator,e", po::value(&evaluators)->composing(),
                     "an evaluator to study (repeatable; default: tooth_passage and zmap)")(
      "spacing", po::value(&spacings_text),
      "grid spacings in mm, comma-separated (default: the scene's, 1/2 and 1/4 of it)")(
      "knob", po::value(&knobs)->composing(),
      "an evaluator's own accuracy knob, e.g. zmap.time_step_fraction=0.9,0.45: one run per value "
      "and spacing")("reference", po::value(&reference),
                     "the evaluator whose finest run is the reference (default: the first)");
  add_batch_options(opts, b);
  LoadedScene loaded = load_batch(args, opts, b, "study");
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  if (evaluators.empty()) evaluators = {"tooth_passage", "zmap"};
  if (reference.empty()) reference = evaluators.front();
  if (std::find(evaluators.begin(), evaluators.end(), reference) == evaluators.end())
    throw InputError(SourceRef{"command line"}, "--reference",
                     "'" + reference + "' is not among the studied evaluators");
  std::vector<double> spacings;
  if (!loaded.vm.count("spacing")) {
    const double s = loaded.scene->table("region").number("spacing");
    spacings = {s, s / 2, s / 4};
  } else {
    spacings = parse_spacings(spacings_text);
  }
  std::sort(spacings.rbegin(), spacings.rend());  // coarse to fine
  std::vector<Knob> knob_list;
  for (const auto& k : knobs) {
    knob_list.push_back(parse_knob(k));
    if (std::find(evaluators.begin(), evaluators.end(), knob_list.back().evaluator) ==
        evaluators.end())
      throw InputError(
          SourceRef{"command line"}, "--knob",
          "'" + k + "': '" + knob_list.back().evaluator + "' is not among the studied evaluators");
  }
  const StudyCases sc = study_cases(b, evaluators, spacings, knob_list);
  const auto lock = lock_batch_output(b, sc.cases);
  const std::vector<CaseResult> results = run_cases(sc.cases, runner_options(b));
  if (Distribution::instance().rank() != 0) return 0;
  const std::size_t ref_index = reference_of(sc, results, reference);
  const CaseResult* ref = ref_index < results.size() ? &results[ref_index] : nullptr;
  ResultTable table;
  std::map<std::string, Series> curves;
  const int failed = study_table(sc, results, ref, table, curves);
  const fs::path dir = b.out_dir;
  table.write_csv((dir / "study.csv").string());
  table.write_markdown((dir / "study.md").string());
  std::vector<Series> list;
  for (auto& [n, s] : curves) list.push_back(s);
  ChartLabels labels;
  labels.title = "Sa error against evaluation time: " + loaded.scene->table("scene").string("name");
  labels.x = "evaluate stage (s)";
  labels.y = "|Sa - Sa(reference)| / Sa(reference) (%)";
  labels.log_x = labels.log_y = true;
  // The reference has no error to plot on a log axis: its time is marked instead.
  if (ref && ref->ok) {
    const auto& c = sc.cases[ref_index].columns;
    labels.marks_x.push_back(
        {"reference: " + c[0].second + " " + c[1].second + " mm", stage(*ref, "evaluate")});
  }
  write_line_chart((dir / "study.png").string(), labels, list);
  std::cout << table.markdown() << "\n"
            << "reference: "
            << (ref ? reference + " at " + sc.cases[ref_index].columns[1].second + " mm"
                    : "none (it failed)")
            << "; " << (dir / "study.csv").string() << "\n";
  return failed ? 3 : 0;
}

}  // namespace topomill::cli
