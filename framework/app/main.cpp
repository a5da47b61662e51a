// topomill: predicts the surface a ball-end mill leaves on a curved workpiece.
#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "interrupt.hpp"
#include "topomill/error.hpp"
#include "topomill/version.hpp"

namespace {

struct Command {
  const char* name;
  int (*run)(const topomill::cli::Args&);
  const char* summary;
};

const Command kCommands[] = {
    {"run", topomill::cli::cmd_run, "simulate a scene and write its outputs"},
    {"check", topomill::cli::cmd_check, "validate a scene and print it resolved"},
    {"plugins", topomill::cli::cmd_plugins, "list the models available, per slot"},
    {"describe", topomill::cli::cmd_describe, "show a model's parameters"},
    {"measure", topomill::cli::cmd_measure, "ISO 25178 parameters of a height-map file"},
    {"compare", topomill::cli::cmd_compare,
     "a simulated surface beside a measured one: registered, differenced, parameters"},
    {"ablate", topomill::cli::cmd_ablate, "each effect off in turn, and swapped models"},
    {"sweep", topomill::cli::cmd_sweep, "the cross product of varied scene keys"},
    {"study", topomill::cli::cmd_study, "accuracy against time, per evaluator and resolution"},
    {"lobes", topomill::cli::cmd_lobes, "stability lobes: critical depth against spindle speed"},
};

void usage(std::ostream& os) {
  os << "usage: topomill COMMAND [OPTIONS]\n\ncommands:\n";
  for (const auto& c : kCommands)
    os << "  " << c.name << std::string(10 - std::string(c.name).size(), ' ') << c.summary << "\n";
  os << "\n'topomill COMMAND --help' shows a command's options.\n"
        "exit codes: 0 ok, 1 internal failure, 2 bad input (scene, option, file), 3 some cases\n"
        "of a batch command failed, 128 + the signal when stopped by SIGINT (130), SIGHUP (129)\n"
        "or SIGTERM (143)\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    usage(std::cout);
    return 0;
  }
  if (name == "--version") {
    std::cout << "topomill " << topomill::kVersion << " (plugin ABI " << topomill::kAbiVersion
              << ")\n";
    return 0;
  }
  topomill::install_interrupt_handler();
  // A case of a batch command stops with it, even when the batch is killed outright (SIGKILL):
  // the batch names itself here, and the kernel sends SIGTERM when it dies.
  if (const char* parent = std::getenv("TOPOMILL_STOP_WITH_PARENT")) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (std::to_string(getppid()) != parent) return 128 + SIGTERM;  // it died before prctl
  }
  for (const auto& c : kCommands) {
    if (name != c.name) continue;
    try {
      return c.run(topomill::cli::Args(argv + 2, argv + argc));
    } catch (const topomill::InputError& e) {
      std::cerr << e.what() << "\n";
      return 2;
    } catch (const topomill::Interrupted& e) {
      std::cerr << e.what() << "\n";
      return 128 + topomill::stop_signal();  // the shell's convention: 130 for SIGINT
    } catch (const topomill::PluginError& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "internal error: " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "error: unknown command '" << name << "'\n\n";
  usage(std::cerr);
  return 2;
}
