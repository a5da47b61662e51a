// Every scene under configs/invalid/ must be refused by `check` and by `run` with exit code 2 and
// the message its header promises ("# expect: ..."; {file} stands for the scene's path), and a
// refused run must leave no output behind. Adding a file adds a regression test.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>

#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {
struct Expectation {
  std::string file, args;
  int exit_code = -1;
  std::vector<std::string> messages;
};

Expectation read_header(const fs::path& path, const std::string& relative) {
  Expectation e;
  e.file = relative;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.rfind("#", 0) == 0) {
    auto value = [&](const std::string& tag) { return line.substr(tag.size()); };
    if (line.rfind("# args: ", 0) == 0) e.args = value("# args: ");
    if (line.rfind("# expect-exit: ", 0) == 0) e.exit_code = std::stoi(value("# expect-exit: "));
    if (line.rfind("# expect: ", 0) == 0)
      e.messages.push_back(
          std::regex_replace(value("# expect: "), std::regex("\\{file\\}"), relative));
  }
  return e;
}
}  // namespace

TEST_CASE("every scene in configs/invalid is refused with its documented message",
          "[cli][errors]") {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(testing::source_dir() + "/configs/invalid"))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  REQUIRE(scenes.size() >= 15);

  for (const auto& path : scenes) {
    const std::string relative = "configs/invalid/" + path.filename().string();
    const Expectation e = read_header(path, relative);
    DYNAMIC_SECTION(relative) {
      REQUIRE(e.exit_code == 2);
      REQUIRE_FALSE(e.messages.empty());
      const std::string out = testing::temp_dir("invalid_" + path.stem().string());
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
