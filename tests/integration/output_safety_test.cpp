// What a run, `measure` and `compare` write, in a directory someone else can write into too: no
// output, lock or staging file is opened through a link planted there, no file that is not the
// run's own is truncated, a place that cannot be written is bad input (exit 2) naming the option,
// and two writers of one file leave one whole result.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kQuick = "configs/examples/quick.toml";
const std::string kVictimText = "someone else's file\n";

// A directory with a file that must not change ("victim.txt").
std::string fresh(const std::string& name) {
  const std::string dir = testing::temp_dir(name);
  fs::create_directories(dir + "/out");
  std::ofstream(dir + "/victim.txt") << kVictimText;
  return dir;
}

// A small measured map to measure and compare: the quick scene's residual.
std::string map_file() {
  static const std::string file = [] {
    const std::string dir = testing::temp_dir("safety_map");
    const auto r = testing::run_topomill("run " + kQuick + " -q --set 'output.formats=[\"x3p\"]' " +
                                         "--out " + dir);
    REQUIRE(r.exit_code == 0);
    return dir + "/height_residual.x3p";
  }();
  return file;
}
}  // namespace

TEST_CASE("a link or a hard link planted at the lock is refused, its target untouched",
          "[safety]") {
  // OUT/.lock planted as a link to another file must not get the run's pid written into it.
  const std::string dir = fresh("planted_lock");
  fs::create_symlink(dir + "/victim.txt", dir + "/out/.lock");
  auto r = testing::run_topomill("run " + kQuick + " -q --out " + dir + "/out");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(".lock' is a symbolic link"));
  CHECK(testing::read_file(dir + "/victim.txt") == kVictimText);
  fs::remove(dir + "/out/.lock");
  fs::create_hard_link(dir + "/victim.txt", dir + "/out/.lock");
  r = testing::run_topomill("run " + kQuick + " -q --out " + dir + "/out");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("linked from elsewhere"));
  CHECK(testing::read_file(dir + "/victim.txt") == kVictimText);
  CHECK_FALSE(fs::exists(dir + "/out/summary.json"));
}

TEST_CASE("links planted at staging and output names are replaced, never written through",
          "[safety]") {
  // Links planted at OUT/summary.json.partial and measure's NAME.partial (the fixed staging
  // names once used) and at the staging names used now must not be followed.
  const std::string dir = fresh("planted_staging");
  const std::string victim = dir + "/victim.txt";
  for (const char* name : {"summary.json.partial", ".incomplete", "height_raw.csv",
                           ".summary.json.partial.AAAAAA", ".incomplete.AAAAAA"})
    fs::create_symlink(victim, dir + "/out/" + name);
  fs::create_directories(dir + "/victim_dir");
  fs::create_symlink(dir + "/victim_dir", dir + "/out/.incomplete.BBBBBB");
  auto r = testing::run_topomill("run " + kQuick + " -q --out " + dir + "/out");
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(testing::read_file(victim) == kVictimText);
  CHECK(fs::is_empty(dir + "/victim_dir"));
  CHECK(fs::is_regular_file(fs::symlink_status(dir + "/out/height_raw.csv")));
  CHECK(fs::exists(dir + "/out/summary.json"));

  for (const char* ext : {"csv", "gsf", "sdf", "x3p"}) {
    INFO(ext);
    const std::string out = dir + "/processed." + ext;
    fs::create_symlink(victim, out + ".partial");
    fs::create_symlink(victim, out);
    r = testing::run_topomill("measure " + map_file() + " --form plane --out " + out);
    INFO(r.err);
    CHECK(r.exit_code == 0);
    CHECK(testing::read_file(victim) == kVictimText);
    CHECK(fs::is_regular_file(fs::symlink_status(out)));
  }
}

TEST_CASE("a place that cannot be written is bad input naming the option", "[safety]") {
  // Read-only targets and a directory in the way are the user's choice: exit 2, not 1.
  const std::string dir = fresh("unwritable");
  fs::create_directories(dir + "/a_directory.csv");
  for (const std::string& out :
       {dir + "/a_directory.csv", dir + "/no/such/dir/x.csv", std::string("/proc/topomill.csv")}) {
    INFO(out);
    const auto r = testing::run_topomill("measure " + map_file() + " --out " + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("key '--out'"));
  }
  const auto r = testing::run_topomill("compare " + map_file() + " " + map_file() +
                                       " --out /proc/topomill_compare");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("key '--out'"));
}

TEST_CASE("two measures writing one file leave one whole result", "[safety]") {
  // With one fixed staging name, one of two writers would fail in some trials and the file could
  // match neither result.
  const std::string dir = fresh("two_writers");
  const std::string a = dir + "/a.csv", b = dir + "/b.csv", both = dir + "/both.csv";
  REQUIRE(testing::run_topomill("measure " + map_file() + " --form plane --out " + a).exit_code ==
          0);
  REQUIRE(testing::run_topomill("measure " + map_file() + " --form none --out " + b).exit_code ==
          0);
  // The files' creation times differ: compare them without their comment lines.
  auto data = [](const std::string& f) {
    std::ifstream in(f);
    std::string line, out;
    while (std::getline(in, line))
      if (line.rfind('#', 0) != 0) out += line + "\n";
    return out;
  };
  for (int trial = 0; trial < 6; ++trial) {
    const int first = testing::spawn_topomill(
        {"measure", map_file(), "--form", "plane", "--out", both}, dir + "/first.log");
    const int second = testing::spawn_topomill(
        {"measure", map_file(), "--form", "none", "--out", both}, dir + "/second.log");
    const int s1 = testing::wait_for(first), s2 = testing::wait_for(second);
    INFO("trial " << trial);
    CHECK((WIFEXITED(s1) && WEXITSTATUS(s1) == 0));
    CHECK((WIFEXITED(s2) && WEXITSTATUS(s2) == 0));
    const std::string got = data(both);
    CHECK((got == data(a) || got == data(b)));
  }
  for (const auto& e : fs::directory_iterator(dir))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
}

TEST_CASE("outputs get the modes the umask gives, as files a user makes", "[safety]") {
  // Staging files (mkostemp: 0600) and directories (mkdtemp: 0700) are private while written;
  // what is moved into place must be readable as the user's umask says.
  const mode_t mask = umask(022);
  umask(mask);
  const std::string dir = fresh("modes");
  REQUIRE(testing::run_topomill("run " + kQuick + " -q --out " + dir + "/out").exit_code == 0);
  REQUIRE(testing::run_topomill("compare " + map_file() + " " + map_file() + " --out " + dir +
                                "/report")
              .exit_code == 0);
  auto mode = [](const std::string& p) {
    return static_cast<unsigned>(fs::status(p).permissions() & fs::perms::all);
  };
  CHECK(mode(dir + "/out/summary.json") == (0666u & ~mask));
  CHECK(mode(dir + "/out/height_raw.csv") == (0666u & ~mask));
  CHECK(mode(dir + "/report") == (0777u & ~mask));
  CHECK(mode(dir + "/report/compare.json") == (0666u & ~mask));
}
