#include "support/run_command.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>

#include "spawn.hpp"

namespace testing {

namespace fs = std::filesystem;

std::string source_dir() {
  return TOPOMILL_SOURCE_DIR;
}
std::string fixture_dir(const std::string& name) {
  return std::string(TOPOMILL_FIXTURE_DIR) + "/" + name;
}

namespace {
// This process's folder under the system's temporary one, removed when the process ends: ctest
// runs each test case as a process of its own, and their folders would otherwise pile up.
// (Children are started by posix_spawn, never forked, so no child runs this destructor.) Set
// TOPOMILL_KEEP_TEST_FILES to keep it, to look into a failure's files.
struct ProcessFolder {
  fs::path path = fs::temp_directory_path() / ("topomill_test_" + std::to_string(getpid()));
  ProcessFolder() = default;
  ProcessFolder(const ProcessFolder&) = delete;
  ProcessFolder& operator=(const ProcessFolder&) = delete;
  ~ProcessFolder() {
    if (std::getenv("TOPOMILL_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};
}  // namespace

std::string temp_dir(const std::string& name) {
  static const ProcessFolder folder;
  fs::path p = folder.path / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p.string();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_topomill(const std::string& args, const std::string& env) {
  const std::string dir = temp_dir("capture");
  fs::create_directories(dir);
  const std::string out = dir + "/out", err = dir + "/err";
  const std::string cmd = "cd '" + source_dir() + "' && " + (env.empty() ? "" : env + " ") +
                          "'" TOPOMILL_EXE "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  // The shell reports a child killed by signal N as exit status 128 + N.
  r.crashed = WIFSIGNALED(status) || (r.exit_code > 128 && r.exit_code < 160);
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

int spawn_topomill(const std::vector<std::string>& args, const std::string& log) {
  // The program resolves scene paths against its working directory: the source tree.
  const fs::path here = fs::current_path();
  fs::current_path(source_dir());
  int pid = -1;
  try {
    pid = topomill::spawn_logged(TOPOMILL_EXE, args, log, /*own_group=*/false);
  } catch (const std::exception&) {
  }
  fs::current_path(here);
  return pid;
}

void wait_until_catching(int pid, int signal) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    bool alive = false, program = false;
    while (std::getline(status, line)) {
      // (Before its exec the child is a copy of this test binary, with the test runner's own
      // handlers: only the program's name says it is running topomill.)
      if (line.rfind("Name:", 0) == 0) program = line == "Name:\ttopomill";
      if (line.rfind("State:", 0) == 0) alive = line.find('Z') == std::string::npos;
      if (line.rfind("SigCgt:", 0) == 0 && alive && program &&
          (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1) & 1))
        return;
    }
    if (!alive) return;  // ended (a zombie until waited for) or gone
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

int wait_for(int pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace testing
