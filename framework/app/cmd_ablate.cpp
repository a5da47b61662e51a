// topomill ablate SCENE [--swap slot=model ...]: the scene as given, with each enabled effect
// switched off in turn (or, --additive, each alone), with all of them off (ideal), and with each
// named alternative model;
// a table of Sa, Sq, Sz and their change against the full model, with run times and stages, a
// bar chart and the residual heat maps side by side on one colour scale.
#include <cmath>
#include <filesystem>
#include <iostream>

#include "batch_options.hpp"
#include "commands.hpp"
#include "distribution.hpp"
#include "io/png_chart.hpp"
#include "io/x3p.hpp"
#include "result_table.hpp"

namespace fs = std::filesystem;

namespace topomill::cli {

namespace {

// Slot names users know from the design, to the scene tables that select them.
std::string table_for(const std::string& slot, const Scene& scene) {
  static const std::map<std::string, std::string> alias = {{"dynamics", "vibration"},
                                                           {"surface", "workpiece"},
                                                           {"shape", "workpiece"},
                                                           {"geometry", "tool"},
                                                           {"topography", "evaluator"}};
  const auto it = alias.find(slot);
  const std::string table = it == alias.end() ? slot : it->second;
  if (!scene.slots.count(table)) {
    std::string known;
    for (const auto& [name, st] : scene.slots) known += (known.empty() ? "" : ", ") + name;
    throw InputError(
        SourceRef{"command line"}, "--swap",
        "'" + slot + "' is not a slot; expected one of " + known + " (or dynamics, surface)");
  }
  return table;
}

std::string percent_change(double v, double full) {
  if (!std::isfinite(v) || !std::isfinite(full) || full == 0) return "";
  return cell(100 * (v - full) / full);
}

// The variants: the full model; each enabled effect off in turn and all off (or, additive, the
// ideal model and each effect alone on it); each swapped model. Every case also writes x3p
// (float64 with the grid's origin), which the side-by-side maps read back.
std::vector<Case> ablation_cases(const BatchOptions& b, const Scene& scene,
                                 const std::vector<std::string>& swaps, bool additive) {
  std::string formats = "output.formats=[\"x3p\"";
  for (const auto& f : scene.table("output").strings("formats"))
    if (f != "x3p") formats += ",\"" + f + "\"";
  formats += "]";
  std::vector<Case> cases;
  auto add = [&](const std::string& name, std::vector<std::string> set) {
    Case c;
    c.id = case_id(name);
    c.columns = {{"variant", name}};
    set.push_back(formats);
    c.overrides = set;
    cases.push_back(c);
  };
  add("full", {});
  const auto effects = scene.enabled_effects();
  std::vector<std::string> all_off;
  for (const auto& e : effects) all_off.push_back(e + ".enabled=false");
  if (additive) {
    // The paper's view: ideal, then each effect alone on top of it.
    if (!effects.empty()) add("ideal", all_off);
    if (effects.size() > 1)
      for (const auto& e : effects) {
        std::vector<std::string> only;
        for (const auto& other : effects)
          if (other != e) only.push_back(other + ".enabled=false");
        add("only " + e, only);
      }
  } else {
    for (const auto& e : effects) add("no " + e, {e + ".enabled=false"});
    if (effects.size() > 1) add("ideal", all_off);
  }
  for (const auto& spec : swaps) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos)
      throw InputError(SourceRef{"command line"}, "--swap",
                       "'" + spec + "': expected slot=model, e.g. dynamics=modal_exact");
    const std::string table = table_for(spec.substr(0, eq), scene);
    const auto& slot = scene.slot(table);
    if (!slot.enabled)
      throw InputError(SourceRef{"command line"}, "--swap",
                       "'" + spec + "': the scene does not use [" + table + "]; enable it (--set " +
                           table + ".enabled=true) to compare its models");
    const std::vector<std::string> set = {table + ".plugin=\"" + spec.substr(eq + 1) + "\""};
    check_variant(b, set, "--swap " + spec, /*check_unused=*/true);
    add(table + "=" + spec.substr(eq + 1), set);
  }
  return cases;
}

// One row per variant (its parameters and their change from the full model), its bars, and its
// residual map when it ran; the number of failed variants.
int ablation_table(const std::vector<Case>& cases, const std::vector<CaseResult>& results,
                   ResultTable& table,
                   std::vector<std::pair<std::string, std::vector<double>>>& bars,
                   std::vector<std::pair<std::string, HeightMap>>& maps) {
  const CaseResult& full = results.front();
  table.header = {"variant",     "effects",     "status",      "Sa_um",  "Sq_um",  "Sz_um",
                  "dSa_percent", "dSq_percent", "dSz_percent", "time_s", "stages", "error"};
  int failed = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const CaseResult& r = results[i];
    const std::string name = cases[i].columns.front().second;
    std::string ran;
    for (const auto& e : r.effects) ran += (ran.empty() ? "" : "+") + e;
    std::vector<std::string> row = {
        name, r.ok ? (ran.empty() ? "none" : ran) : "",
        r.ok ? "ok" : "failed (exit " + std::to_string(r.exit_code) + ")"};
    for (const char* p : {"Sa", "Sq", "Sz"}) row.push_back(cell(parameter(r, p)));
    for (const char* p : {"Sa", "Sq", "Sz"})
      row.push_back(percent_change(parameter(r, p), parameter(full, p)));
    row.push_back(r.ok ? cell(r.wall_s) : "");
    row.push_back(stage_list(r));
    row.push_back(r.error);
    table.rows.push_back(row);
    bars.emplace_back(
        name, std::vector<double>{parameter(r, "Sa"), parameter(r, "Sq"), parameter(r, "Sz")});
    if (r.ok)
      maps.emplace_back(name, read_x3p((fs::path(r.dir) / "height_residual.x3p").string()).map);
    failed += r.ok ? 0 : 1;
  }
  return failed;
}

}  // namespace

int cmd_ablate(const Args& args) {
  BatchOptions b;
  std::vector<std::string> swaps;
  bool additive = false;
  po::options_description opts(
      "topomill ablate SCENE [--swap slot=model ...] [--jobs N]: the scene with each enabled "
      "effect off in turn, all off (ideal), and each swapped model; writes ablation.csv, "
      "ablation.md, ablation.png (Sa per variant) and ablation_maps.png (resumable)");
  opts.add_options()("swap", po::value(&swaps)->composing(),
                     "an alternative model for one variant, e.g. --swap dynamics=modal_exact")(
      "additive", po::bool_switch(&additive),
      "each effect alone on the ideal model instead of each switched off in turn");
  add_batch_options(opts, b);
  LoadedScene loaded = load_batch(args, opts, b, "ablation");
  if (!loaded.scene) {
    std::cout << opts << "\n";
    return 0;
  }
  const Scene& scene = *loaded.scene;

  std::vector<Case> cases = ablation_cases(b, scene, swaps, additive);
  if (cases.size() == 1)
    std::cerr << "topomill: the scene enables no effect and --swap names no model: the "
                 "ablation has the full model only\n";

  const auto lock = lock_batch_output(b, cases);
  const std::vector<CaseResult> results = run_cases(cases, runner_options(b));
  if (Distribution::instance().rank() != 0) return 0;

  ResultTable table;
  std::vector<std::pair<std::string, std::vector<double>>> bars;
  std::vector<std::pair<std::string, HeightMap>> maps;
  const int failed = ablation_table(cases, results, table, bars, maps);
  const fs::path dir = b.out_dir;
  table.write_csv((dir / "ablation.csv").string());
  table.write_markdown((dir / "ablation.md").string());
  ChartLabels labels;
  labels.title = "Sa, Sq, Sz per variant: " + scene.table("scene").string("name");
  labels.y = "height parameter (µm)";
  write_bar_chart((dir / "ablation.png").string(), labels, {"Sa", "Sq", "Sz"}, bars);
  // The residual lies along the surface (s) when the nominal form was removed, else in plan.
  const bool along = scene.table("analysis").string("form") == "nominal";
  if (!maps.empty())
    write_heatmap_panels((dir / "ablation_maps.png").string(), maps, "x (mm)",
                         along ? "s (mm)" : "y (mm)");
  std::cout << table.markdown() << "\n"
            << results.size() - failed << " of " << results.size() << " variants ok; "
            << (dir / "ablation.csv").string() << "\n";
  return failed ? 3 : 0;
}

}  // namespace topomill::cli
