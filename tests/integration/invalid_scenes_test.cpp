// Every scene under configs/invalid/ must be refused by `check` and by `run` with exit code 2 and
// the message its header promises, and a refused run must leave no output behind. Adding a file
// adds a regression test.
#include <catch2/catch.hpp>
#include <filesystem>

#include "support/run_command.hpp"
#include "support/scene_header.hpp"

namespace fs = std::filesystem;

TEST_CASE("every scene in configs/invalid is refused with its documented message",
          "[cli][errors]") {
  const auto scenes = testing::scenes_in("configs/invalid");
  REQUIRE(scenes.size() >= 15);
  for (const auto& relative : scenes) {
    const auto e = testing::read_scene_header(relative);
    DYNAMIC_SECTION(relative) {
      REQUIRE(e.exit_code == 2);
      REQUIRE_FALSE(e.messages.empty());
      const std::string out = testing::temp_dir("invalid_" + fs::path(relative).stem().string());
      for (const std::string command : {"check", "run"}) {
        std::string args = command + " " + relative + " " + e.args + " -q";
        if (command == "run") args += " --out '" + out + "'";
        const auto r = testing::run_topomill(args);
        INFO(command << ": " << r.err);
        CHECK_FALSE(r.crashed);
        CHECK(r.exit_code == e.exit_code);
        for (const auto& m : e.messages) CHECK(r.err.find(m) != std::string::npos);
      }
      CHECK_FALSE(fs::exists(out));  // refused before any output
    }
  }
}

TEST_CASE("every hard case finishes with finite heights or stops with its message", "[hard]") {
  const auto scenes = testing::scenes_in("configs/validation/hard");
  REQUIRE(scenes.size() >= 8);
  // Both evaluators: tooth_passage (the default) once searched forever for crossings next to the
  // ball's rim (steep_plane), where the lag's rate has no bound.
  const std::string evaluator = GENERATE(as<std::string>{}, "tooth_passage", "zmap");
  for (const auto& relative : scenes) {
    const auto e = testing::read_scene_header(relative);
    DYNAMIC_SECTION(relative << " with " << evaluator) {
      const std::string out =
          testing::temp_dir("hard_" + fs::path(relative).stem().string() + "_" + evaluator);
      const auto r = testing::run_topomill("run " + relative + " -q --threads 2 --out '" + out +
                                           "' --set evaluator.plugin=" + evaluator);
      INFO(r.err);
      CHECK_FALSE(r.crashed);
      REQUIRE(r.exit_code == e.exit_code);
      for (const auto& m : e.messages) CHECK(r.err.find(m) != std::string::npos);
      if (e.exit_code == 0) {
        const std::string csv = testing::read_file(out + "/height_residual.csv");
        REQUIRE_FALSE(csv.empty());
        CHECK(csv.find("nan") == std::string::npos);
        CHECK(csv.find("inf") == std::string::npos);
        CHECK(fs::exists(out + "/summary.json"));
      } else {
        CHECK_FALSE(fs::exists(out + "/summary.json"));
      }
    }
  }
}
