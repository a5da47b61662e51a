#include "support/scene_header.hpp"

#include <algorithm>
#include <fstream>
#include <regex>

#include "support/run_command.hpp"

namespace testing {

SceneHeader read_scene_header(const std::string& relative) {
  SceneHeader e;
  e.file = relative;
  std::ifstream in(source_dir() + "/" + relative);
  std::string line;
  while (std::getline(in, line) && line.rfind("#", 0) == 0) {
    auto value = [&](const std::string& tag) { return line.substr(tag.size()); };
    // `{fixture:NAME}` in the arguments: that fixture plugin's directory (tests/fixtures).
    if (line.rfind("# args: ", 0) == 0) {
      e.args = value("# args: ");
      std::smatch m;
      while (std::regex_search(e.args, m, std::regex("\\{fixture:([a-z_]+)\\}")))
        e.args = m.prefix().str() + "'" + fixture_dir(m[1].str()) + "'" + m.suffix().str();
    }
    if (line.rfind("# expect-exit: ", 0) == 0) e.exit_code = std::stoi(value("# expect-exit: "));
    if (line.rfind("# expect: ", 0) == 0)
      e.messages.push_back(
          std::regex_replace(value("# expect: "), std::regex("\\{file\\}"), relative));
  }
  return e;
}

std::vector<std::string> scenes_in(const std::string& relative_dir) {
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(source_dir() + "/" + relative_dir))
    if (entry.path().extension() == ".toml")
      out.push_back(relative_dir + "/" + entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace testing
