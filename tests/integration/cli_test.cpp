// The command line as a user meets it: help, listings, check, run and its outputs.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/scene_header.hpp"

namespace fs = std::filesystem;
using testing::run_topomill;

TEST_CASE("every command answers --help and an unknown command is refused", "[cli]") {
  for (const std::string c : {"run", "check", "plugins", "describe"}) {
    const auto r = run_topomill(c + " --help");
    INFO(c);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("--plugin-path") != std::string::npos);
  }
  const auto bad = run_topomill("frobnicate");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("unknown command 'frobnicate'") != std::string::npos);
  const auto opt = run_topomill("plugins --no-such-option");
  CHECK(opt.exit_code == 2);
  CHECK(opt.err.find("no-such-option") != std::string::npos);
}

TEST_CASE("plugins lists every built-in model per slot, as text and JSON", "[cli][plugins]") {
  const auto text = run_topomill("plugins");
  REQUIRE(text.exit_code == 0);
  for (const std::string m : {"ball_end_loxodrome", "ball_end_constant_lead", "convex_arc",
                              "concave_arc", "inclined_plane", "zmap"})
    CHECK(text.out.find(m) != std::string::npos);
  CHECK(text.out.find("lib/topomill/plugins/libtopomill_zmap.so") != std::string::npos);

  const auto json = run_topomill("plugins --json");
  REQUIRE(json.exit_code == 0);
  CHECK(json.out.find("\"search_path\"") != std::string::npos);
  CHECK(json.out.find("\"topography_evaluator\"") != std::string::npos);
  CHECK(json.out.find("\"name\": \"zmap\"") != std::string::npos);
}

TEST_CASE("describe shows a model's schema and answers an unknown name with the known ones",
          "[cli]") {
  const auto r = run_topomill("describe convex_arc --json");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"name\": \"radius\"") != std::string::npos);
  CHECK(r.out.find("\"unit\": \"mm\"") != std::string::npos);
  CHECK(r.out.find("\"required\": true") != std::string::npos);

  const auto bad = run_topomill("describe convex_ark");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("did you mean 'convex_arc'?") != std::string::npos);
  CHECK(bad.err.find("Known models: ball_end_constant_lead") != std::string::npos);
}

TEST_CASE("check prints the resolved scene with defaults and overrides applied", "[cli][scene]") {
  const auto r = run_topomill(
      "check configs/examples/quick.toml -q --set cutting.feed_per_tooth=0.2 "
      "--set path.phase_shift=90");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("feed_per_tooth = 0.2") != std::string::npos);
  CHECK(r.out.find("phase_shift = 90") != std::string::npos);
  CHECK(r.out.find("spindle_direction = 'cw'") != std::string::npos);  // a default
  CHECK(r.out.find("catw_margin = 1.5") != std::string::npos);         // a plugin default
}

TEST_CASE("run writes complete outputs and a summary naming plugins and stages", "[cli][run]") {
  const std::string out = testing::temp_dir("run_quick");
  const auto r = run_topomill("run configs/examples/quick.toml -q --out '" + out + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  for (const std::string f : {"summary.json", "height_raw.csv", "height_residual.csv",
                              "height_raw.gsf", "height_residual.gsf", "height_residual.png"})
    CHECK(fs::exists(out + "/" + f));
  for (const auto& e : fs::directory_iterator(out))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
  const std::string summary = testing::read_file(out + "/summary.json");
  CHECK(summary.find("\"roughness\"") != std::string::npos);
  CHECK(summary.find("\"Sa\"") != std::string::npos);
  CHECK(summary.find("libtopomill_tooth_passage.so") != std::string::npos);
  CHECK(summary.find("\"evaluate\"") != std::string::npos);
  CHECK(summary.find("\"effects\": []") != std::string::npos);
  CHECK(r.out.find("Sa ") != std::string::npos);
}

TEST_CASE("every committed scene under paper, validation and examples passes check",
          "[cli][scene]") {
  std::vector<std::string> scenes;
  for (const std::string dir : {"configs/paper", "configs/validation", "configs/examples"})
    for (const auto& s : testing::scenes_in(dir)) scenes.push_back(s);
  REQUIRE(scenes.size() >= 20);
  for (const auto& s : scenes) {
    const auto r = run_topomill("check " + s + " -q");
    INFO(s << ": " << r.err);
    CHECK(r.exit_code == 0);
  }
}

TEST_CASE("every plugin folder holds its README and an example scene that runs",
          "[cli][scene][plugins]") {
  int plugins = 0;
  for (const auto& dir : fs::directory_iterator(testing::source_dir() + "/plugins")) {
    if (!dir.is_directory() || dir.path().filename() == "common") continue;  // shared headers
    ++plugins;
    const std::string name = dir.path().filename().string();
    INFO(name);
    CHECK(fs::exists(dir.path() / "README.md"));
    REQUIRE(fs::exists(dir.path() / "example.toml"));
    const std::string out = testing::temp_dir("example_" + name);
    const auto r =
        run_topomill("run plugins/" + name + "/example.toml -q --threads 2 --out '" + out + "'");
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(out + "/summary.json"));
    // The example shows its own plugin at work.
    CHECK(testing::read_file(out + "/summary.json").find("libtopomill_" + name + ".so") !=
          std::string::npos);
  }
  CHECK(plugins >= 12);
}

TEST_CASE("measure on run's x3p output gives the run's own parameters", "[cli][metrology]") {
  const std::string out = testing::temp_dir("run_x3p");
  const auto r = run_topomill("run configs/examples/quick.toml -q --out '" + out +
                              "' --set 'output.formats=[\"x3p\", \"sdf\", \"vts\"]'");
  REQUIRE(r.exit_code == 0);
  for (const std::string f : {"height_residual.x3p", "height_raw.sdf", "height_residual.vts"})
    CHECK(fs::exists(out + "/" + f));
  const auto m = run_topomill("measure '" + out + "/height_residual.x3p' --json");
  REQUIRE(m.exit_code == 0);
  const std::string summary = testing::read_file(out + "/summary.json");
  // Every parameter: x3p holds metres, so the heights come back to a rounding (1e-16 relative).
  const auto measured = nlohmann::json::parse(m.out).at("roughness");
  const auto run = nlohmann::json::parse(summary).at("roughness");
  REQUIRE(run.size() == 10);
  for (const auto& [name, p] : run.items()) {
    INFO(name);
    CHECK(measured.at(name).at("value").get<double>() ==
          Approx(p.at("value").get<double>()).epsilon(1e-12));
    CHECK(measured.at(name).at("unit") == p.at("unit"));
  }
}

TEST_CASE("analysis.parameters and measure --parameters report the same full set",
          "[cli][metrology]") {
  // A run asked for every parameter at non-default settings writes them all, each with its
  // setting; measure on its residual with the same options gives the same numbers; the processed
  // surface measure writes (--out) measures the same again.
  const std::string out = testing::temp_dir("run_all_parameters");
  const auto r =
      run_topomill("run configs/examples/quick.toml -q --out '" + out +
                   "' --set 'output.formats=[\"x3p\"]' --set 'analysis.parameters=[\"all\"]' "
                   "--set analysis.volume_p=5 --set analysis.acf_threshold=0.3");
  REQUIRE(r.exit_code == 0);
  const auto run = nlohmann::json::parse(testing::read_file(out + "/summary.json")).at("roughness");
  CHECK(run.size() == 27);
  CHECK(run.at("Vmp").at("method") == "p = 5 %");
  CHECK(run.at("Sal").at("method") == "s = 0.3");
  const std::string options = " --parameters all --volume-p 5 --acf-threshold 0.3 --json";
  const auto m = run_topomill("measure '" + out + "/height_residual.x3p'" + options + " --out '" +
                              out + "/processed.x3p'");
  REQUIRE(m.exit_code == 0);
  const auto again = run_topomill("measure '" + out + "/processed.x3p'" + options);
  REQUIRE(again.exit_code == 0);
  const auto measured = nlohmann::json::parse(m.out).at("roughness");
  const auto reread = nlohmann::json::parse(again.out).at("roughness");
  for (const auto& [name, p] : run.items()) {
    INFO(name);
    if (!p.contains("value")) continue;  // undefined for this map, said why
    CHECK(measured.at(name).at("value").get<double>() ==
          Approx(p.at("value").get<double>()).epsilon(1e-9).margin(1e-12));
    CHECK(reread.at(name).at("value").get<double>() ==
          Approx(p.at("value").get<double>()).epsilon(1e-9).margin(1e-12));
  }
  // Refused: a format that cannot be written, and settings out of order, naming the option.
  auto bad = run_topomill("measure '" + out + "/height_residual.x3p' --out '" + out + "/p.png'");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("key '--out': cannot write") != std::string::npos);
  bad = run_topomill("measure '" + out + "/height_residual.x3p' --volume-p 90 --volume-q 80");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("key '--volume-q': volume_q 80 % is not above volume_p 90 %") !=
        std::string::npos);
  bad = run_topomill("measure '" + out + "/height_residual.x3p' --parameters Sa,Vmcc");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("did you mean 'Vmc'?") != std::string::npos);
  CHECK_FALSE(fs::exists(out + "/p.png"));
}

TEST_CASE("a run that would not fit in memory is refused before any work, naming the key",
          "[cli][errors][resources]") {
  const std::string out = testing::temp_dir("memory");
  // The grid dominates: 16 x 16 nodes and the Z-map's maps do not fit in 10 KiB.
  auto r = testing::run_topomill(
      "run configs/examples/quick.toml -q --set evaluator.plugin=zmap --out '" + out + "'",
      "TOPOMILL_MEMORY_LIMIT=10K");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("configs/examples/quick.toml:25:11: error: key 'region.spacing': the run "
                   "would need about") != std::string::npos);
  CHECK(r.err.find("and 0.00977 MiB are available") != std::string::npos);
  // The evaluator's own tables dominate: tooth_passage's 30 000 passes at a 10 nm step-over.
  r = testing::run_topomill(
      "run configs/examples/quick.toml -q --set evaluator.plugin=tooth_passage "
      "--set cutting.stepover=1e-5 --out '" +
          out + "'",
      "TOPOMILL_MEMORY_LIMIT=50M");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--set cutting.stepover=1e-5: error: key 'cutting.stepover': the run would "
                   "need about 117 MiB") != std::string::npos);
  CHECK(r.err.find("raise cutting.stepover (what tooth_passage's memory grows with)") !=
        std::string::npos);
  // A limit beyond 64 bits is no limit (1e99 wrapped around to "0 MiB are available").
  r = testing::run_topomill("check configs/examples/quick.toml -q", "TOPOMILL_MEMORY_LIMIT=1e99");
  CHECK(r.exit_code == 0);
  // The force/dynamics samples dominate: a fast mode sets a tiny time step on a coarse grid.
  r = testing::run_topomill(
      "run tests/stability/base.toml -q --set region.spacing=0.05 --set vibration.enabled=true "
      "--set 'vibration.modes=[{axis=\"z\", frequency=40000.0, damping=0.02, stiffness=1e9}]' "
      "--out '" +
          out + "'",
      "TOPOMILL_MEMORY_LIMIT=20M");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("error: key 'vibration': the run would need about") != std::string::npos);
  CHECK(r.err.find("the fastest vibration mode sets the time step") != std::string::npos);
  r = testing::run_topomill("run configs/examples/quick.toml -q --out '" + out + "'",
                            "TOPOMILL_MEMORY_LIMIT=lots");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("key 'TOPOMILL_MEMORY_LIMIT': 'lots' is not a positive byte count") !=
        std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
}
