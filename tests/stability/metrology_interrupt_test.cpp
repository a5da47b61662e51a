// `measure` and `compare` honour SIGINT, SIGTERM and SIGHUP within 2 s at any moment (reading,
// processing, parameters, writing a large x3p), exit with 128 + the signal and write nothing.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <thread>

#include "io/x3p.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
// A large map (2401 x 2401 points: a 46 MB x3p, seconds to measure with every parameter): marks
// along both axes, so that nothing about it is degenerate.
std::string big_map() {
  static const std::string file = [] {
    const std::string dir = testing::temp_dir("interrupt_metrology");
    fs::create_directories(dir);
    topomill::Grid g;
    g.nx = g.ny = 2401;
    g.dx = g.dy = 0.001;
    topomill::HeightMap m(g);
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        m.at(i, j) =
            1e-3 * (std::sin(g.x(i) / 0.05) + 0.3 * std::cos(g.y(j) / 0.013 + 0.2 * g.x(i)));
    topomill::write_x3p(dir + "/big.x3p", m);
    return dir + "/big.x3p";
  }();
  return file;
}

// Starts `args`, signals it `after` seconds after it catches the signal; it must end with 128 + the
// signal within 2 s (or have finished first, exit 0), leaving `out` absent unless it finished.
void stopped(const std::vector<std::string>& args, const std::string& out, double after,
             int signal) {
  const std::string log = out + ".log";
  fs::remove_all(out);
  const int pid = testing::spawn_topomill(args, log);
  REQUIRE(pid > 0);
  testing::wait_until_catching(pid, signal);
  std::this_thread::sleep_for(std::chrono::duration<double>(after));
  const auto sent = Clock::now();
  kill(pid, signal);
  const int status = testing::wait_for(pid);
  const double took = std::chrono::duration<double>(Clock::now() - sent).count();
  INFO(args[0] << " signalled " << signal << " after " << after
               << " s: " << testing::read_file(log));
  REQUIRE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 0) return;  // finished before the signal came
  CHECK(WEXITSTATUS(status) == 128 + signal);
  CHECK(took < 2.0);
  CHECK_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
}
}  // namespace

TEST_CASE("measure stops on a signal at any stage and writes nothing", "[stability][kill]") {
  // Not: finish, write everything and exit 0 after Ctrl-C or SIGTERM; nor go on writing a large
  // x3p for minutes.
  const std::string map = big_map();
  const std::string out = fs::path(map).parent_path() / "measured.x3p";
  int finished_early = 0;
  for (const double after : {0.05, 0.5, 1.5, 3.0})
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
      stopped({"measure", map, "--form", "plane", "--filter-l", "0.25", "--parameters", "all",
               "--out", out},
              out, after, signal);
      finished_early += fs::exists(out);
    }
  CHECK(finished_early < 3);  // the moments fall inside the work, not after it
}

TEST_CASE("compare stops on a signal at any stage and writes nothing", "[stability][kill]") {
  const std::string map = big_map();
  const std::string out = fs::path(map).parent_path() / "compared";
  for (const double after : {0.05, 0.5, 1.5, 3.0})
    stopped({"compare", map, map, "--form", "plane", "--parameters", "all", "--out", out}, out,
            after, SIGTERM);
}
