#include "support/zip_files.hpp"

#include <zip.h>

#include <catch2/catch.hpp>

namespace testing {

void write_zip(const std::string& path,
               const std::vector<std::pair<std::string, std::string>>& files) {
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  REQUIRE(z);
  for (const auto& [name, content] : files)
    zip_file_add(z, name.c_str(), zip_source_buffer(z, content.data(), content.size(), 0), 0);
  REQUIRE(zip_close(z) == 0);
}

}  // namespace testing
