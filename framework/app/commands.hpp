// One function per sub-command; each returns the process exit code and throws InputError for
// bad input (exit 2).
#pragma once

#include <string>
#include <vector>

namespace topomill::cli {

using Args = std::vector<std::string>;

int cmd_run(const Args& args);
int cmd_check(const Args& args);
int cmd_plugins(const Args& args);
int cmd_describe(const Args& args);
int cmd_measure(const Args& args);
int cmd_compare(const Args& args);
int cmd_sweep(const Args& args);
int cmd_ablate(const Args& args);
int cmd_study(const Args& args);
int cmd_lobes(const Args& args);

}  // namespace topomill::cli
