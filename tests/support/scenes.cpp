#include "support/scenes.hpp"

#include <sstream>

namespace testing {

std::string paper_scene(const std::string& workpiece, double lambda_deg, double size_x,
                        double size_s, double spacing) {
  std::ostringstream s;
  s.precision(17);
  s << "[tool]\nplugin = 'ball_end_loxodrome'\nradius = 5.0\nteeth = 2\nhelix_angle = 30.0\n"
    << "[workpiece]\n"
    << workpiece << "\n"
    << "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = 0.1\ndepth_of_cut = 0.3\n"
    << "stepover = 0.3\n"
    << "[region]\nlambda = " << lambda_deg << "\nsize = [" << size_x << ", " << size_s
    << "]\nspacing = " << spacing << "\n";
  return s.str();
}

std::string dynamics_tables() {
  return "[force]\nplugin = 'armarego'\n"
         "[vibration]\nenabled = true\nplugin = 'modal_rk4'\nmodes = [\n"
         "  { axis = 'x', frequency = 785.0, damping = 0.02, stiffness = 17400000.0 },\n"
         "  { axis = 'y', frequency = 1750.0, damping = 0.03, stiffness = 30300000.0 },\n]\n"
         "[deflection]\nenabled = true\nplugin = 'cantilever'\n";
}

topomill::RunResult run_scene(const std::string& toml, const std::vector<std::string>& overrides,
                              unsigned threads, const std::vector<std::string>& plugin_dirs) {
  auto doc = topomill::SceneDocument::parse_string(toml, "test-scene.toml");
  for (const auto& o : overrides) doc.apply_override(o);
  std::vector<topomill::PluginCatalog::Dir> dirs;
  for (const auto& d : plugin_dirs) dirs.push_back({d, "--plugin-path"});
  dirs.push_back({topomill::PluginCatalog::builtin_dir(), "built-in"});
  topomill::PluginCatalog catalog(dirs);
  topomill::Scene scene = doc.resolve(catalog);
  topomill::RunOptions options;
  options.threads = threads;
  return topomill::run_pipeline(scene, catalog, options);
}

topomill::Surface paper_surface(double size, double spacing) {
  topomill::Surface s;
  s.map = run_scene(paper_scene("plugin = 'convex_arc'\nradius = 50.0", 30.0, size, size, spacing))
              .residual;
  s.source = "paper lambda 30";
  return s;
}

}  // namespace testing
