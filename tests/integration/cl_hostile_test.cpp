// Cutter-location data as a careless or hostile user gives it: data that never reaches the part,
// centres inside it, feeds out of any range, files that are no files, and files that are not CL
// data at all. Each is refused with exit 2 naming the file and line (or the scene's key), by
// `check` as by `run`, and nothing is written.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

// The plate raster of configs/examples/cl_plate_raster.toml (R 5 mm, ap 0.02 mm: centres at
// z = 4.98) reading `file` with `point`.
std::string scene(const std::string& file, const std::string& point = "centre") {
  return "[tool]\nplugin = 'ball_end_constant_lead'\nradius = 5.0\nteeth = 2\n"
         "[workpiece]\nplugin = 'inclined_plane'\nangle = 0.0\n"
         "[cutting]\nspindle_speed = 4000\nfeed_per_tooth = 0.1\ndepth_of_cut = 0.02\n"
         "stepover = 0.3\n"
         "[path]\nplugin = 'cl_file'\nfile = '" +
         file + "'\npoint = '" + point +
         "'\n"
         "[region]\nlambda = 0.0\nsize = [0.3, 0.3]\nspacing = 0.01\n"
         "[output]\nformats = ['csv']\n";
}

// Five passes along Y at x = -0.6 ... 0.6, each from y = -0.92 to 0.92, at height z and with the
// feed column `feed` (mm/min) when not empty.
std::string raster(double z, const std::string& feed = "") {
  std::ostringstream s;
  s.precision(17);
  s << (feed.empty() ? "x,y,z\n" : "x,y,z,f\n");
  for (int k = -2; k <= 2; ++k) {
    for (double y : {-0.92, 0.92})
      s << 0.3 * k << "," << y << "," << z << (feed.empty() ? "" : "," + feed) << "\n";
    s << "\n";
  }
  return s.str();
}

struct Case {
  std::string dir;
  explicit Case(const std::string& name) : dir(testing::temp_dir("cl_hostile_" + name)) {
    fs::create_directories(dir);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir + "/" + name) << text;
  }
  // `check` and `run` alike: exit 2, every `expected` in the message, nothing written.
  void refused(const std::string& toml, const std::vector<std::string>& expected) const {
    write("scene.toml", toml);
    for (const char* command : {"check", "run"}) {
      const auto r = testing::run_topomill(
          std::string(command) + " " + dir + "/scene.toml -q" +
          (std::string(command) == "run" ? " --out " + dir + "/out" : std::string()));
      INFO(command << ": " << r.err);
      CHECK(r.exit_code == 2);
      for (const auto& e : expected) CHECK(r.err.find(e) != std::string::npos);
      CHECK_FALSE(fs::exists(dir + "/out"));
    }
  }
};

}  // namespace

TEST_CASE("CL data that never reaches the part is refused, naming the file and line",
          "[cl][hostile]") {
  // Passes 1 mm above the part, or centre data read as tips, would give a flat map (Sa 6e-13 um)
  // with exit 0.
  const Case c("above");
  c.write("above.csv", raster(5.98));
  c.refused(scene("above.csv"), {"above.csv:2:1: error: key 'path.file'", "never touches"});
  c.write("centres.csv", raster(4.98));
  c.refused(scene("centres.csv", "tip"), {"centres.csv:", "never touches", "path.point"});
}

TEST_CASE("CL centres inside the part are refused: the ball's equator would cut", "[cl][hostile]") {
  // A centre 1 mm below the surface, which the README promises to refuse; tips read as centres
  // put every centre below it too.
  const Case c("below");
  c.write("below.csv", raster(-1.0));
  c.refused(scene("below.csv"), {"below.csv:2:1: error: key 'path.file'", "1 mm below"});
  c.write("tips.csv", raster(-0.02));
  c.refused(scene("tips.csv"), {"tips.csv:2:1", "below the workpiece surface", "path.point"});
}

TEST_CASE("a CL feed far outside any cut is refused at its line", "[cl][hostile]") {
  // 1e-300 mm/min would run on for ever without the long-run warning; 1e300 would overflow the
  // times ("internal error", exit 1).
  const Case c("feed");
  for (const std::string feed : {"1e-300", "1e300"}) {
    INFO(feed);
    c.write("feed.csv", raster(4.98, feed));
    c.refused(scene("feed.csv"),
              {"feed.csv:2:1: error: key 'path.file': the feed to the next point is", "mm/min"});
  }
}

TEST_CASE("a CL point far beyond any part is refused at its own line", "[cl][hostile]") {
  // A point at y = 1e308 overflows the path's lengths: refused before they are formed.
  const Case c("far");
  c.write("far.csv", "x,y,z\n0,1e308,4.98\n0,0.92,4.98\n");
  c.refused(scene("far.csv"), {"far.csv:2:1: error: key 'path.file': the point lies 1e+308 mm"});
}

TEST_CASE("a CL file must be a regular file, read within a bound", "[cl][hostile]") {
  // A FIFO would block the reader until signalled; /dev/zero would be read for 256 MiB.
  const Case c("special");
  const std::string fifo = c.dir + "/fifo.csv";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  c.refused(scene("fifo.csv"), {"scene.toml:", "key 'path.file'", "not a regular file"});
  c.refused(scene("/dev/zero"), {"key 'path.file'", "not a regular file"});
  c.refused(scene("."), {"key 'path.file'", "is a directory"});
}

TEST_CASE("a file that is no CL data keeps its content out of the refusal", "[cl][hostile]") {
  // A scene from elsewhere may name any file: its first line must not come back in the refusal.
  const Case c("disclosure");
  c.write("secret.txt", "root:secret-hash-1234:0:0:root\nmore:secret:lines\n");
  for (const char* format : {"csv", "apt"}) {
    INFO(format);
    std::string toml = scene("secret.txt");
    toml.insert(toml.find("point ="), std::string("format = '") + format + "'\n");
    c.write("scene.toml", toml);
    const auto r = testing::run_topomill("check " + c.dir + "/scene.toml -q");
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("secret.txt:1:1"));
    CHECK(r.err.find("secret-hash") == std::string::npos);
    CHECK(r.err.find("root") == std::string::npos);
  }
}
