// Runs scenes in-process (with the built-in plugins) for tests that inspect the height maps.
#pragma once

#include <string>
#include <vector>

#include "metrology/surface.hpp"
#include "run/pipeline.hpp"

namespace testing {

// The paper's tool and cutting conditions on `workpiece` (the [workpiece] table's body).
std::string paper_scene(const std::string& workpiece, double lambda_deg, double size_x,
                        double size_s, double spacing);

// The residual map of the paper's lambda = 30 deg scene on the convex arc (fz 0.1, ae 0.3 mm),
// `size` mm square at `spacing`, as a surface to measure or compare.
topomill::Surface paper_surface(double size, double spacing);

// Vibration (two modes) and deflection with the armarego force: tables to append to a scene.
std::string dynamics_tables();

// Resolves `toml` with `overrides` ("table.key=value", as --set) and runs it; `plugin_dirs` are
// searched before the built-in plugins (fixture plugins).
topomill::RunResult run_scene(const std::string& toml,
                              const std::vector<std::string>& overrides = {}, unsigned threads = 2,
                              const std::vector<std::string>& plugin_dirs = {});

}  // namespace testing
