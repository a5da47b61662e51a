// Writing zip archives by hand in tests: x3p files, whole or deliberately broken.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace testing {

// A zip at `path` holding `files` (name, content), compressed as libzip chooses.
void write_zip(const std::string& path,
               const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace testing
