// The fingerprint a resumed sweep compares: it follows a library's bytes, not its time stamp.
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "code_fingerprint.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

TEST_CASE("the code fingerprint follows the libraries' bytes, not their times", "[batch]") {
  const std::string dir = testing::temp_dir("fingerprint");
  fs::create_directories(dir);
  const std::string a = dir + "/liba.so", b = dir + "/libb.so";
  std::ofstream(a, std::ios::binary) << "first build";
  std::ofstream(b, std::ios::binary) << "other plugin";
  const std::string first = topomill::code_fingerprint({a, b});
  CHECK(first.size() == 8);
  CHECK(topomill::code_fingerprint({b, a}) == first);  // order of slots does not matter
  // Touched (a rebuild that wrote the same bytes): the same code.
  fs::last_write_time(a, fs::last_write_time(a) + std::chrono::hours(1));
  CHECK(topomill::code_fingerprint({a, b}) == first);
  // Rebuilt with other bytes: other code.
  std::ofstream(a, std::ios::binary) << "second build";
  CHECK(topomill::code_fingerprint({a, b}) != first);
  // Gone: never the fingerprint of a readable file.
  const std::string second = topomill::code_fingerprint({a, b});
  fs::remove(a);
  CHECK(topomill::code_fingerprint({a, b}) != second);
  CHECK(topomill::code_fingerprint({a, b}) != first);
}
