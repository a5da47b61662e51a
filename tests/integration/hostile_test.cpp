// What a careless or hostile user does (issue 18): every case here once crashed, hung, ate memory,
// wrote NaN or answered with a wrong number or a misleading message. Each must now be refused
// with exit 2 and a message saying what is wrong, quickly, within a memory limit where the old
// behaviour was to allocate gigabytes, and without printing NaN or Inf. The signals, the output
// lock and the plugin trust cases live beside their subjects (interruption_test, batch_test,
// fixture_plugins_test); the scenes in configs/invalid/ are the scene-level cases.
#include <zip.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "support/run_command.hpp"
#include "support/zip_files.hpp"

namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// rows x cols CSV of `value(i, j)`, cells joined by `sep`.
std::string grid_csv(int rows, int cols, const std::function<std::string(int, int)>& value,
                     const std::string& sep = ",") {
  std::ostringstream os;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) os << (i ? sep : "") << value(i, j);
    os << "\n";
  }
  return os.str();
}

// A Gwyddion simple field with the header lines given and `points` float32 zeros after it.
std::string gsf(const std::string& header_lines, std::size_t points, std::size_t trailing = 0) {
  std::string h = "Gwyddion Simple Field 1.0\n" + header_lines;
  h.append(4 - h.size() % 4, '\0');
  return h + std::string(points * 4 + trailing, '\0');
}

// A minimal x3p main.xml: nx x ny doubles in bindata/data.bin, optionally a valid-points mask.
std::string x3p_xml(long nx, long ny, bool with_mask) {
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1><Axes>"
        "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CX>"
        "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CY>"
        "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3>"
        "<MatrixDimension><SizeX>"
     << nx << "</SizeX><SizeY>" << ny
     << "</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>"
        "<PointDataLink>bindata/data.bin</PointDataLink>"
     << (with_mask ? "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>" : "")
     << "</DataLink></Record3></p:ISO5436_2>\n";
  return os.str();
}

// Rewrites the uncompressed size of every entry in a zip's local and central headers (what a
// hand-made file can claim): offsets 22 and 24 from their signatures.
void claim_size(const std::string& path, std::uint32_t size) {
  std::ifstream in(path, std::ios::binary);
  std::string b((std::istreambuf_iterator<char>(in)), {});
  for (const auto& [sig, at] : {std::pair<std::string, std::size_t>{"PK\x03\x04", 22},
                                std::pair<std::string, std::size_t>{"PK\x01\x02", 24}})
    for (auto p = b.find(sig); p != std::string::npos; p = b.find(sig, p + 4))
      std::memcpy(b.data() + p + at, &size, 4);
  write_text(path, b);
}

struct Hostile {
  int defect;          // the item of issue 18
  std::string args;    // {dir}: a directory holding the files made for the case
  std::string prefix;  // shell words before the program: a time or memory limit, variables
  int exit_code;
  std::vector<std::string> expect;  // in the error output
};

}  // namespace

TEST_CASE("hostile inputs are refused with exit 2, quickly and within bounded memory",
          "[hostile][errors]") {
  const std::string dir = testing::temp_dir("hostile");
  fs::create_directories(dir);
  // Files the cases read.
  write_text(dir + "/flat.csv", grid_csv(20, 20, [](int i, int j) {
               return std::to_string(0.5 * ((i * 7 + j * 3) % 5) + 0.01 * j);
             }));
  write_text(dir + "/huge.csv", grid_csv(20, 20, [](int i, int j) {
               return (i + j) % 2 ? std::string("1e300") : std::string("-1e300");
             }));
  write_text(dir + "/junk.csv", "1,2,3\n4,1.5abc,6\n");
  write_text(dir + "/spaces.csv", "10 11 12\n13 14 15\n");
  write_text(dir + "/semicolon.csv", grid_csv(
                                         20, 20, [](int, int) { return "1"; }, ";"));
  write_text(dir + "/xres_twice.gsf", gsf("XRes = 10\nXRes = 20\nYRes = 10\n", 200));
  write_text(dir + "/trailing.gsf", gsf("XRes = 20\nYRes = 20\n", 400, 800));
  write_text(dir + "/xres_huge.gsf", gsf("XRes = 100000\nYRes = 100000\n", 4));
  write_text(dir + "/numpoints.sdf",
             "aISO-1.0\nNumPoints = 20.5\nNumProfiles = 2\nXscale = 1e-6\nYscale = 1e-6\n"
             "Zscale = 1e-6\n*\n1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21\n*\n");
  testing::write_zip(dir + "/no_valid.x3p", {{"main.xml", x3p_xml(4, 4, true)},
                                             {"bindata/data.bin", std::string(16 * 8, '\0')},
                                             {"bindata/valid.bin", std::string(2, '\0')}});
  testing::write_zip(dir + "/too_many.x3p",
                     {{"main.xml", x3p_xml(20000, 20000, false)}, {"bindata/data.bin", "tiny"}});
  testing::write_zip(dir + "/lying.x3p", {{"main.xml", x3p_xml(100, 100, false)},
                                          {"bindata/data.bin", std::string(100 * 100 * 8, '\0')}});
  claim_size(dir + "/lying.x3p", 0xF0000000u);  // "4 GiB" from a few hundred bytes
  fs::create_directories(dir + "/scene_dir");
  fs::create_symlink("/dev/zero", dir + "/zero.csv");
  fs::create_symlink("/dev/zero", dir + "/zero.gsf");
  fs::create_symlink("/dev/urandom", dir + "/urandom.toml");
  write_text(dir + "/bad_out.toml",
             testing::read_file("configs/examples/quick.toml") + "dir = \"/dev/null/out\"\n");

  const std::string quick = "timeout -s KILL 20";
  const std::string small = "ulimit -v 1500000 && timeout -s KILL 20";  // 1.5 GB of address space
  const std::string q = "configs/examples/quick.toml";
  const std::vector<Hostile> cases = {
      // 3: the L-filter's kernel was as long as its cut-off (3 GB at 1e6 mm, overflow at 1e100).
      {3, "measure {dir}/flat.csv --spacing 0.01 --filter-l 1e6", small, 0, {}},
      {3,
       "measure {dir}/flat.csv --spacing 0.01 --filter-l 1e100",
       small,
       2,
       {"key '--filter-l': expected a cut-off (0: no L-filter) from 0 to 1e6 mm, got 1e+100"}},
      // 5: the zip header believed; no memory check in measure.
      {5, "measure {dir}/lying.x3p", small, 2, {"lying.x3p: error:"}},
      {5,
       "measure {dir}/too_many.x3p",
       "export TOPOMILL_MEMORY_LIMIT=1G && " + small,
       2,
       {"too_many.x3p: error: the map has 4e+08 points: reading and measuring it needs about"}},
      // 7: NaN and Inf printed; infinite spacings accepted.
      {7,
       "measure {dir}/huge.csv --spacing 0.01",
       quick,
       2,
       {"huge.csv: error: ", "is not finite for these heights"}},
      {7, "measure {dir}/huge.csv --spacing 0.01 --json", quick, 2, {"is not finite"}},
      {7,
       "measure {dir}/flat.csv --spacing inf",
       quick,
       2,
       {"key '--spacing': expected a node spacing"}},
      {7, "measure {dir}/flat.csv --spacing 1e308", quick, 2, {"key '--spacing'"}},
      // 9: the first number of a cell was kept.
      {9,
       "measure {dir}/junk.csv --spacing 0.01",
       quick,
       2,
       {"junk.csv:2:2: error: expected a finite number (um), got '1.5abc'"}},
      {9,
       "measure {dir}/spaces.csv --spacing 0.01",
       quick,
       2,
       {"spaces.csv:1:1: error: expected a finite number (um), got '10 11 12' (cells are "
        "separated by commas"}},
      {9, "measure {dir}/semicolon.csv --spacing 0.01", quick, 2, {"semicolon.csv:1:1: error:"}},
      // 10: an infinite S-filter was ignored.
      {10, "measure {dir}/flat.csv --spacing 0.01 --filter-s inf", quick, 2, {"'--filter-s'"}},
      // 13: meaningless input measured.
      {13,
       "measure {dir}/no_valid.x3p",
       quick,
       2,
       {"no_valid.x3p: error: the map has 0 valid points: expected at least 4"}},
      {13, "measure {dir}/flat.csv --spacing 0.01 --filter-l nan", quick, 2, {"'--filter-l'"}},
      {13,
       "measure {dir}/xres_twice.gsf",
       quick,
       2,
       {"xres_twice.gsf: error: XRes is given twice in the header"}},
      {13,
       "measure {dir}/trailing.gsf",
       quick,
       2,
       {"trailing.gsf: error: 800 bytes follow the 400 float32 points: expected none"}},
      {13,
       "measure {dir}/numpoints.sdf",
       quick,
       2,
       {"numpoints.sdf: error: NumPoints and NumProfiles must be whole numbers"}},
      // 14: messages that pointed the wrong way.
      {14,
       "measure {dir}/flat.csv --spacing 0.01 --filter-l -1",
       quick,
       2,
       {"key '--filter-l': expected a cut-off"}},
      {14,
       "measure {dir}/xres_huge.gsf",
       quick,
       2,
       {"xres_huge.gsf: error: XRes x YRes = 1e+10 points: expected at most 4e8"}},
      {14,
       "check " + q + " --set a.b.c.d.e=1",
       quick,
       2,
       {"--set a.b.c.d.e=1: error: key 'a': unknown key"}},
      {14,
       "check {dir}/scene_dir",
       quick,
       2,
       {"scene_dir: error: is a directory: expected a scene file (TOML)"}},
      {14,
       "run {dir}/bad_out.toml -q",
       quick,
       2,
       {"bad_out.toml:34:7: error: key 'output.dir': cannot create the output directory "
        "'/dev/null/out'"}},
      // 15: devices read forever.
      {15,
       "check /dev/zero",
       quick,
       2,
       {"/dev/zero: error: is not a regular file (a device or a pipe): expected a scene file"}},
      {15,
       "measure {dir}/zero.csv --spacing 0.01",
       quick,
       2,
       {"zero.csv: error: is not a regular file (a device or a pipe): expected a CSV height map"}},
      {15, "measure {dir}/zero.gsf", quick, 2, {"zero.gsf: error: is not a regular file"}},
      {15, "run {dir}/urandom.toml", quick, 2, {"urandom.toml: error: is not a regular file"}},
      // 16: ambiguous batch arguments.
      {16,
       "sweep " + q + " --vary region.lambda=10,20 --vary region.lambda=30 --out {dir}/v",
       quick,
       2,
       {"'region.lambda' is varied twice"}},
      {16, "study " + q + " --spacing '' --out {dir}/s", quick, 2, {"key '--spacing': ''"}},
      {16,
       "study " + q + " --knob zmap.time_step_fraction= --out {dir}/k",
       quick,
       2,
       {"an empty value in the list"}},
      {16,
       "check " + q + " --set \"$(printf 'scene.name=\"x\"\\n[evil]\\na=1')\"",
       quick,
       2,
       {"the value holds a line break: expected one TOML value on one line"}},
  };
  for (const auto& c : cases) {
    std::string args = c.args;
    for (auto p = args.find("{dir}"); p != std::string::npos; p = args.find("{dir}"))
      args.replace(p, 5, dir);
    DYNAMIC_SECTION("defect " << c.defect << ": " << args) {
      const auto started = std::chrono::steady_clock::now();
      const auto r = testing::run_topomill(args, c.prefix);
      const double took =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      INFO(r.err);
      CHECK_FALSE(r.crashed);  // also: not killed by the time limit
      CHECK(r.exit_code == c.exit_code);
      CHECK(took < 10);
      for (const auto& m : c.expect) CHECK(r.err.find(m) != std::string::npos);
      for (const char* bad : {"nan", "inf ", "NaN", "Infinity", "internal error"})
        CHECK(r.out.find(bad) == std::string::npos);
      CHECK(r.err.find("internal error") == std::string::npos);
    }
  }
}
