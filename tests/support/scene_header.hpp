// Scenes that carry their expected outcome in header comments:
//   # args: --set key=value        extra command-line words
//   # expect-exit: 2               the exit code
//   # expect: {file}:6:1: error: ...  a line the error output must contain ({file}: the scene path)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace testing {

struct SceneHeader {
  std::string file;  // as passed on the command line, relative to the source directory
  std::string args;
  int exit_code = -1;
  std::vector<std::string> messages;
};

SceneHeader read_scene_header(const std::string& relative_path);
// The .toml files of a directory under the source tree, sorted, as relative paths.
std::vector<std::string> scenes_in(const std::string& relative_dir);

}  // namespace testing
