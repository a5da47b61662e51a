// The scene and the run: a scene is its TOML text, the name it came under (its file, against
// which its relative paths resolve) and the overrides set() added, as `--set` adds them; each
// call parses it afresh, exactly as the command line does.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <mutex>

#include "calls.hpp"
#include "cli.hpp"
#include "describe.hpp"
#include "run/pipeline.hpp"
#include "run/run_outputs.hpp"
#include "scene.hpp"

namespace topomill::python {

namespace {

struct SceneText {
  std::string text, name;
  std::vector<std::string> overrides;  // "key=value", value in TOML
  std::vector<std::string> plugin_paths;
  bool scene_plugin_paths = true;  // whether the scene may name plugin directories
};

SceneDocument document(const SceneText& s) {
  SceneDocument doc = SceneDocument::parse_string(s.text, s.name);
  for (const auto& o : s.overrides) doc.apply_override(o);
  return doc;
}

struct Resolved {
  std::unique_ptr<PluginCatalog> catalog;
  Scene scene;
};

Resolved resolve(const SceneText& s, bool check_unused) {
  const SceneDocument doc = document(s);
  cli::Common common;
  common.plugin_paths = s.plugin_paths;
  Resolved r;
  r.catalog = std::make_unique<PluginCatalog>(
      cli::search_path(common, doc.plugin_paths(s.scene_plugin_paths)));
  r.scene = doc.resolve(*r.catalog, check_unused);
  return r;
}

// A finished run kept in memory: the height maps stay where the pipeline left them, and the
// arrays handed to Python are views of them that keep this object alive.
struct RunRecord {
  std::unique_ptr<PluginCatalog> catalog;  // first, so released last: the models' libraries
  RunResult result;
  std::string summary;  // summary.json's content, no files written
};

py::array_t<double> view(const HeightMap& m, py::handle owner) {
  const auto nx = static_cast<py::ssize_t>(m.grid.nx), ny = static_cast<py::ssize_t>(m.grid.ny);
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  py::array_t<double> a({ny, nx}, {nx * item, item}, m.z.data(), owner);
  // The run's result, not a scratch copy: changing it would make it disagree with its summary.
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::dict grid_dict(const Grid& g) {
  py::dict d;
  d["nx"] = g.nx, d["ny"] = g.ny, d["x0"] = g.x0, d["y0"] = g.y0, d["dx"] = g.dx, d["dy"] = g.dy;
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<SceneText>(m, "SceneText")
      .def(py::init<std::string, std::string, std::vector<std::string>, std::vector<std::string>,
                    bool>(),
           py::arg("text"), py::arg("name"), py::arg("overrides"), py::arg("plugin_paths"),
           py::arg("scene_plugin_paths"));

  m.def(
      "read_scene",
      [](const std::string& path) {
        std::string bytes;
        interruptible([&] { bytes = SceneDocument::read_file(path); }, ErrorKind::Scene);
        return py::bytes(bytes);
      },
      "A scene file's bytes, read as the command line reads them.");

  m.def(
      "parse_scene",
      [](const SceneText& s) { interruptible([&] { document(s); }, ErrorKind::Scene); },
      "Parses the text and applies the overrides: SceneError for malformed TOML or a bad key.");

  m.def(
      "resolve_scene",
      [](const SceneText& s) {
        interruptible([&] { resolve(s, /*check_unused=*/false); }, ErrorKind::Scene);
      },
      "Checks every key the run uses against its schema, as a sweep checks each value first.");

  m.def(
      "check_scene",
      [](const SceneText& s, unsigned threads) {
        std::string text;
        interruptible(
            [&] {
              with_python_names([&] { cli::check_threads(threads); }, "check()");
              Resolved r = resolve(s, /*check_unused=*/true);
              prepare(r.scene, *r.catalog, threads);
              text = to_toml_text(r.scene.to_toml());
            },
            ErrorKind::Scene);
        return text;
      },
      "Validates every table and the models built from them; returns the resolved TOML.");

  py::class_<RunRecord, std::shared_ptr<RunRecord>>(m, "RunRecord")
      .def_property_readonly(
          "raw", [](py::object self) { return view(self.cast<RunRecord&>().result.raw, self); })
      .def_property_readonly(
          "residual",
          [](py::object self) { return view(self.cast<RunRecord&>().result.residual, self); })
      .def_property_readonly("raw_grid",
                             [](const RunRecord& r) { return grid_dict(r.result.raw.grid); })
      .def_property_readonly("residual_grid",
                             [](const RunRecord& r) { return grid_dict(r.result.residual.grid); })
      .def_property_readonly("unrolled",
                             [](const RunRecord& r) { return r.result.settings.unrolled(); })
      .def_property_readonly(
          "parameters", [](const RunRecord& r) { return reported_parameters(r.result.parameters); })
      .def_property_readonly(
          "undefined", [](const RunRecord& r) { return undefined_parameters(r.result.parameters); })
      .def_property_readonly("stages",
                             [](const RunRecord& r) {
                               py::list out;
                               for (const auto& s : r.result.stages)
                                 out.append(py::make_tuple(s.name, s.seconds));
                               return out;
                             })
      .def_property_readonly("summary", [](const RunRecord& r) { return r.summary; });

  m.def(
      "run_scene",
      [](const SceneText& s, unsigned threads) {
        auto record = std::make_shared<RunRecord>();
        interruptible(
            [&] {
              // One run at a time: a stop request (Ctrl-C) is the process's, and would stop
              // every run going on; runs from several threads take turns.
              static std::mutex one_run;
              const std::lock_guard<std::mutex> turn(one_run);
              const auto started = std::chrono::steady_clock::now();
              with_python_names([&] { cli::check_threads(threads); }, "run()");
              Resolved r = resolve(s, /*check_unused=*/false);
              RunOptions options;
              options.threads = threads;
              record->result = run_pipeline(r.scene, *r.catalog, options);
              record->summary = summary_json(record->result, {}, 0.0, started);
              record->catalog = std::move(r.catalog);
            },
            ErrorKind::Scene);
        return record;
      },
      "Runs the scene in this process, the GIL released; Ctrl-C stops it (KeyboardInterrupt).");
}

}  // namespace topomill::python
