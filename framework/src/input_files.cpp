#include "topomill/input_files.hpp"

#include <algorithm>
#include <mutex>

#include "io/read_file.hpp"

namespace topomill {

namespace {
// One run per process in batch commands (each case is a process of its own); in-process runs
// (tests) clear the list as a run is prepared.
std::mutex& lock() {
  static std::mutex m;
  return m;
}
std::vector<std::string>& files() {
  static std::vector<std::string> f;
  return f;
}
}  // namespace

void record_input_file(const std::string& path) {
  std::lock_guard<std::mutex> hold(lock());
  if (std::find(files().begin(), files().end(), path) == files().end()) files().push_back(path);
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes,
                            const std::string& what) {
  std::string bytes = read_file_bounded(path, max_bytes, what);
  record_input_file(path);
  return bytes;
}

std::vector<std::string> recorded_input_files() {
  std::lock_guard<std::mutex> hold(lock());
  return files();
}

void clear_recorded_input_files() {
  std::lock_guard<std::mutex> hold(lock());
  files().clear();
}

}  // namespace topomill
