// Runs the topomill program as a user would and captures what it says.
#pragma once

#include <string>
#include <vector>

namespace testing {

struct CommandResult {
  int exit_code = -1;    // the process's exit status; -1 if it did not exit normally
  bool crashed = false;  // killed by a signal (segfault, abort)
  std::string out, err;
};

// `args` is appended to the program path as shell words; runs in the source directory.
// `env` (e.g. "TOPOMILL_PLUGIN_PATH=/x") is prefixed to the command when not empty.
CommandResult run_topomill(const std::string& args, const std::string& env = "");

// Starts the program without a shell (so that signals reach it, not a shell), in the source
// directory, with stdout and stderr to `log`. Returns its pid.
int spawn_topomill(const std::vector<std::string>& args, const std::string& log);
// Waits for a spawned program; returns its raw wait status.
int wait_for(int pid);
// Waits (up to 30 s) until a spawned program catches `signal` (Linux: its SigCgt mask in
// /proc), or has ended. A signal sent before that meets the default action: the program has not
// reached main() yet, and a test timed from the spawn would fail by the machine's load alone.
void wait_until_catching(int pid, int signal);

std::string source_dir();
std::string fixture_dir(const std::string& name);
// A fresh empty directory under the build tree's temporary area.
std::string temp_dir(const std::string& name);
std::string read_file(const std::string& path);

}  // namespace testing
