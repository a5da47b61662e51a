// topomill: predicts the surface a ball-end mill leaves on a curved workpiece.
#include <iostream>

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
    {"ablate", topomill::cli::cmd_ablate, "each effect off in turn, and swapped models"},
    {"sweep", topomill::cli::cmd_sweep, "the cross product of varied scene keys"},
    {"study", topomill::cli::cmd_study, "accuracy against time, per evaluator and resolution"},
};

void usage(std::ostream& os) {
  os << "usage: topomill COMMAND [OPTIONS]\n\ncommands:\n";
  for (const auto& c : kCommands)
    os << "  " << c.name << std::string(10 - std::string(c.name).size(), ' ') << c.summary << "\n";
  os << "\n'topomill COMMAND --help' shows a command's options.\n"
        "exit codes: 0 ok, 1 internal failure, 2 bad input (scene, option, file), 130 "
        "interrupted\n";
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
  for (const auto& c : kCommands) {
    if (name != c.name) continue;
    try {
      return c.run(topomill::cli::Args(argv + 2, argv + argc));
    } catch (const topomill::InputError& e) {
      std::cerr << e.what() << "\n";
      return 2;
    } catch (const topomill::Interrupted& e) {
      std::cerr << e.what() << "\n";
      return 130;  // the shell's convention for a SIGINT
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
