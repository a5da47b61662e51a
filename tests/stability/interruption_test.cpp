// Outputs are whole or absent (issue #9): real runs are killed (SIGKILL) at moments spread over
// their whole duration, writing included, and interrupted (SIGINT) while they compute. Whatever
// is left must read whole, summary.json must only ever vouch for whole files, and a rerun into the
// same directory must succeed.
#include <signal.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <regex>
#include <thread>

#include "metrology/read_surface.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// Whether a staging directory (.incomplete.XXXXXX) of `dir` holds `name`; with "", whether
// there is one at all.
bool staged(const std::string& dir, const std::string& name) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(".incomplete", 0) == 0 &&
        (name.empty() || fs::exists(it->path() / name)))
      return true;
  return false;
}

// Every visible file reads whole; those summary.json lists exist.
void check_whole(const std::string& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.front() == '.' || !e.is_regular_file()) continue;  // .incomplete/: unsealed pieces
    INFO(e.path());
    const std::string ext = e.path().extension().string();
    CHECK(fs::file_size(e.path()) > 0);
    if (ext == ".csv" || ext == ".gsf" || ext == ".x3p" || ext == ".sdf")
      CHECK_NOTHROW(topomill::read_surface(e.path().string(), 0));
    else if (ext == ".vts")
      CHECK(testing::read_file(e.path().string()).find("</VTKFile>") != std::string::npos);
    else if (ext == ".png")
      CHECK(testing::read_file(e.path().string()).find("IEND") != std::string::npos);
  }
  const std::string summary = testing::read_file(dir + "/summary.json");
  if (summary.empty()) return;
  CHECK(summary.find("\"roughness\"") != std::string::npos);
  const std::regex listed("\"(height_[a-z]+\\.[a-z3]+)\"");
  for (std::sregex_iterator it(summary.begin(), summary.end(), listed), end; it != end; ++it)
    CHECK(fs::exists(dir + "/" + (*it)[1].str()));
}

const std::vector<std::string> kLongWrite = {
    "run",
    "configs/examples/quick.toml",
    "-q",
    "--set",
    "evaluator.plugin=\"tooth_passage\"",
    "--set",
    "region.spacing=0.002",
    "--set",
    "output.formats=[\"csv\",\"gsf\",\"x3p\",\"sdf\",\"vts\",\"png\"]"};

std::vector<std::string> with_out(std::vector<std::string> args, const std::string& out) {
  args.push_back("--out");
  args.push_back(out);
  return args;
}

}  // namespace

TEST_CASE("a run killed at any moment leaves only whole files, and a rerun succeeds",
          "[stability][kill]") {
  const std::string out = testing::temp_dir("killed");
  const std::string log = testing::temp_dir("killed.log");
  const auto t0 = Clock::now();
  REQUIRE(WEXITSTATUS(testing::wait_for(testing::spawn_topomill(with_out(kLongWrite, out), log))) ==
          0);
  const double full = std::chrono::duration<double>(Clock::now() - t0).count();
  check_whole(out);
  // Moments from the start to past the end of a whole run, so that some fall in the writing.
  constexpr int kKills = 16;
  for (int k = 0; k < kKills; ++k) {
    const double at = full * 1.1 * k / (kKills - 1);
    const int pid = testing::spawn_topomill(with_out(kLongWrite, out), log);
    REQUIRE(pid > 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(at));
    kill(pid, SIGKILL);
    testing::wait_for(pid);
    INFO("killed after " << at << " s of a " << full << " s run");
    check_whole(out);
  }
  const int status = testing::wait_for(testing::spawn_topomill(with_out(kLongWrite, out), log));
  CHECK(WEXITSTATUS(status) == 0);
  check_whole(out);
  CHECK(fs::exists(out + "/summary.json"));
  CHECK_FALSE(staged(out, ""));
}

TEST_CASE("SIGINT, SIGTERM and SIGHUP stop a run promptly with a message and write nothing",
          "[stability][kill]") {
  // The evaluator (the reference Z-map, ~20 s) and the force stage of a scene with dynamics;
  // SIGTERM (kill, timeout, schedulers) and SIGHUP (a closed terminal) as Ctrl-C (issue 18).
  struct Case {
    std::string scene;
    int signal;
    std::string name;
  };
  for (const auto& c : {Case{"configs/paper/lambda30.toml", SIGINT, "SIGINT"},
                        Case{"configs/paper/lambda30_fz01_dynamics.toml", SIGINT, "SIGINT"},
                        Case{"configs/paper/lambda30.toml", SIGTERM, "SIGTERM"},
                        Case{"configs/paper/lambda30.toml", SIGHUP, "SIGHUP"},
                        Case{"tests/stability/steep_slow_node.toml", SIGINT, "SIGINT"}}) {
    DYNAMIC_SECTION(c.scene << " " << c.name) {
      const std::string out = testing::temp_dir("interrupted");
      const std::string log = testing::temp_dir("interrupted.log");
      // zmap: the paper's algorithm takes seconds on these scenes, long enough to be stopped.
      const int pid = testing::spawn_topomill(
          {"run", c.scene, "-q", "--set", "evaluator.plugin=zmap", "--out", out}, log);
      REQUIRE(pid > 0);
      testing::wait_until_catching(pid, c.signal);
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      const auto sent = Clock::now();
      kill(pid, c.signal);
      const int status = testing::wait_for(pid);
      const double took = std::chrono::duration<double>(Clock::now() - sent).count();
      INFO(testing::read_file(log));
      REQUIRE(WIFEXITED(status));
      CHECK(WEXITSTATUS(status) == 128 + c.signal);
      CHECK(took < 2.0);  // a check between rows, steps and passes: not the end of a stage
      CHECK(testing::read_file(log).find("interrupted (" + c.name + ")") != std::string::npos);
      CHECK_FALSE(fs::exists(out + "/summary.json"));
      CHECK_FALSE(fs::exists(out));  // the directory it made is removed again
    }
  }
}

TEST_CASE("a stop request while the outputs are written seals nothing new", "[stability][kill]") {
  // Issue 18: a Ctrl-C during writing was ignored and the run sealed its result (exit 0).
  const std::string out = testing::temp_dir("interrupted_writing");
  const std::string log = testing::temp_dir("interrupted_writing.log");
  const int pid = testing::spawn_topomill(with_out(kLongWrite, out), log);
  REQUIRE(pid > 0);
  // Stop as soon as the first staged file appears: the outputs are being written.
  const auto started = Clock::now();
  while (!staged(out, "height_raw.csv") && Clock::now() - started < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  const auto sent = Clock::now();
  kill(pid, SIGINT);
  const int status = testing::wait_for(pid);
  const double took = std::chrono::duration<double>(Clock::now() - sent).count();
  INFO(testing::read_file(log));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(took < 2.0);
  CHECK_FALSE(fs::exists(out + "/summary.json"));
  check_whole(out);
}

TEST_CASE("one writer per output directory: a second run is refused naming the holder, or waits",
          "[stability][lock]") {
  // Issue 18: two runs into one --out staged into one .incomplete/ and sealed a mix of both.
  const std::string out = testing::temp_dir("locked");
  const std::string log = testing::temp_dir("locked.log");
  const std::vector<std::string> slow = {"run",   "configs/paper/lambda30.toml", "-q",
                                         "--set", "evaluator.plugin=zmap",       "--out",
                                         out};  // seconds long
  const int first = testing::spawn_topomill(slow, log);
  REQUIRE(first > 0);
  const auto started = Clock::now();
  while (!fs::exists(out + "/.lock") && Clock::now() - started < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto second =
      testing::run_topomill("run configs/examples/quick.toml -q --out '" + out + "'");
  CHECK(second.exit_code == 2);
  CHECK(second.err.find("command line: error: key '--out': the output directory '" + out +
                        "' is in use by another topomill run (pid " + std::to_string(first) +
                        ")") != std::string::npos);
  // --wait: the second run starts when the first is gone (here: stopped), and writes.
  const std::string wait_log = testing::temp_dir("locked_wait.log");
  const int waiting = testing::spawn_topomill(
      {"run", "configs/examples/quick.toml", "-q", "--wait", "--out", out}, wait_log);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  CHECK_FALSE(fs::exists(out + "/summary.json"));  // still waiting
  kill(first, SIGINT);
  CHECK(WEXITSTATUS(testing::wait_for(first)) == 130);
  const int status = testing::wait_for(waiting);
  INFO(testing::read_file(wait_log));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(testing::read_file(out + "/summary.json").find("quick example") != std::string::npos);
  // A directory named like an output file is refused before anything changes (was exit 1).
  fs::remove(out + "/height_raw.csv");
  fs::create_directories(out + "/height_raw.csv");
  const auto blocked =
      testing::run_topomill("run configs/examples/quick.toml -q --out '" + out + "'");
  CHECK(blocked.exit_code == 2);
  CHECK(blocked.err.find("'" + out + "/height_raw.csv' is a directory: expected a file there") !=
        std::string::npos);
  CHECK(fs::exists(out + "/summary.json"));  // the previous result still stands
}
