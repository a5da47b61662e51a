// scene -> models -> path -> [force -> dynamics, deformation] -> evaluator -> form removal ->
// parameters. Stages run only when the scene calls for them, and each is timed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "layout.hpp"
#include "metrology/parameters.hpp"
#include "metrology/roughness.hpp"
#include "plugin_catalog.hpp"
#include "run/run_settings.hpp"
#include "run/stage_clock.hpp"
#include "scene.hpp"
#include "topomill/deformation.hpp"
#include "topomill/dynamics_model.hpp"
#include "topomill/force_model.hpp"
#include "topomill/path_model.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/tool_geometry.hpp"
#include "topomill/topography_evaluator.hpp"

namespace topomill {

struct RunOptions {
  unsigned threads = 1;
  // Called with (stage, fraction done); may be empty.
  std::function<void(const std::string&, double)> progress;
};

struct RunResult {
  RunSettings settings;  // what the stages and the output writer read of the scene
  HeightMap raw;         // Z-map heights (mm) over the XY grid
  HeightMap residual;    // after form removal (mm), on the unrolled (x, s) grid or the XY grid
  Roughness roughness;   // of `residual`, in mm (convert at the output)
  ParameterValues parameters;  // of `residual`: those [analysis] parameters selects, as reported
  std::vector<StageTime> stages;
  WorkCounts work;
  std::vector<std::string> effects;  // enabled effect tables that ran
  double dynamics_step = 0;          // s, the force/dynamics time grid (0: no effects)
  double peak_force = 0;             // N, largest |F| over all samples
  double peak_correction = 0;        // mm, largest path correction component
  Layout layout;
  // Files the models read besides the scene (topomill/input_files.hpp), each with the CRC-32 of
  // its bytes when read.
  std::vector<std::pair<std::string, std::string>> input_files;
};

// The models a run uses, constructed, and the grid and tool path: everything that can reject a
// scene, done before any expensive work (`topomill check` stops here).
struct Prepared {
  std::shared_ptr<ToolGeometry> tool;
  std::shared_ptr<SurfaceShape> surface;
  std::shared_ptr<PathModel> path;
  std::shared_ptr<TopographyEvaluator> evaluator;
  // Made only when an enabled effect needs them; null otherwise.
  std::shared_ptr<ForceModel> force;
  std::shared_ptr<DynamicsModel> dynamics;
  std::vector<std::pair<std::string, std::shared_ptr<Deformation>>> deformations;
  Layout layout;
  ParameterSettings parameter_settings;      // [analysis], checked
  std::vector<std::string> parameter_names;  // [analysis] parameters, selected
};

// What the evaluator is asked for a prepared scene: tool, path, contact range, threads.
EvaluationRequest evaluation_request(const Prepared& m, unsigned threads);

// Throws InputError for scenes the model cannot represent, or that would not fit in memory with
// `threads` evaluator threads.
Prepared prepare(const Scene& scene, const PluginCatalog& catalog, unsigned threads = 1);

// Throws InputError for scenes the model cannot represent, std::runtime_error if a stage produces
// a non-finite value, Interrupted after SIGINT.
RunResult run_pipeline(const Scene& scene, const PluginCatalog& catalog, const RunOptions& options);

}  // namespace topomill
