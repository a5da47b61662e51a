// cl_file's reader: what the CSV and APT CL forms say, read as written (passes, axes, feeds,
// units), and every damaged or unsupported file refused at its line and column with what was
// expected.
#include <catch2/catch.hpp>
#include <string>

#include "cl_file/cl_reader.hpp"

namespace cl = topomill::plugins::cl;

namespace {

// The error a text is refused with: "line:column: message".
std::string refusal(const std::string& text, cl::Format format) {
  try {
    cl::read_text(text, format);
  } catch (const cl::ReadError& e) {
    return std::to_string(e.line) + ":" + std::to_string(e.column) + ": " + e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("CL reader: CSV passes, axes and feeds as written", "[cl]") {
  const std::string text =
      "# comment\n"
      "X, Y ,z,I,J,K,f\n"
      "0,0,1,0,0,2,600\n"
      "+1.5,-2e-1,1,0,0.6,0.8,1200\r\n"
      "1.5,-0.2,1,0,0.6,0.8,900\n"  // the point again: no move, left out
      "\n"
      "# a single point is no pass\n"
      "9,9,9,0,0,1,100\n"
      "\n"
      "2,0,1,1,0,1,60\n"
      "3,0,1,1,0,1,60\n";
  const cl::Data d = cl::read_text(text, cl::Format::Csv);
  CHECK(d.has_axis);
  REQUIRE(d.passes.size() == 2);
  REQUIRE(d.passes[0].size() == 2);
  CHECK(d.passes[0][1].position == Eigen::Vector3d(1.5, -0.2, 1));
  CHECK(d.passes[0][0].axis == Eigen::Vector3d(0, 0, 1));  // normalised
  CHECK((d.passes[0][1].axis - Eigen::Vector3d(0, 0.6, 0.8)).norm() < 1e-15);
  CHECK(d.passes[0][1].feed == 1200);
  CHECK(d.passes[0][1].line == 4);  // the repeat on line 5 is left out
  CHECK((d.passes[1][0].axis - Eigen::Vector3d(1, 0, 1).normalized()).norm() < 1e-15);
  // Without i, j, k the axis is vertical; without f the feed is not given (the scene's).
  const cl::Data v = cl::read_text("x,y,z\n0,0,0\n1,0,0\n", cl::Format::Csv);
  CHECK_FALSE(v.has_axis);
  CHECK(v.passes.at(0).at(1).axis == Eigen::Vector3d::UnitZ());
  CHECK(std::isnan(v.passes[0][1].feed));
}

TEST_CASE("CL reader: APT motion, feeds, rapids, units and continuations", "[cl]") {
  const std::string text =
      "PARTNO/TEST $$ a comment\n"
      "UNITS/MM\n"
      "MULTAX\n"
      "CUTTER/10.0\n"
      "FROM/0,0,50\n"
      "RAPID\n"
      "GOTO/0,0,1\n"
      "FEDRAT/MMPM,300\n"
      "GOTO/1,0,1, $\n"
      "   0,0,1\n"
      "goto / 2 , 0 , 1\n"
      "RAPID\n"
      "GOTO/2,5,1\n"
      "FEDRAT/ 600\n"
      "UNITS/INCHES\n"
      "GOTO/0,0,0.5,0,0.6,0.8\n"
      "GOTO/1,0,0.5\n"
      "FEDRAT/IPM, 10\n"
      "GOTO/2,0,0.5\n"
      "END-OF-PATH\n"
      "FINI\n";
  const cl::Data d = cl::read_text(text, cl::Format::Apt);
  REQUIRE(d.passes.size() == 2);  // FROM alone is no pass; RAPID ends the first
  REQUIRE(d.passes[0].size() == 3);
  CHECK(std::isnan(d.passes[0][0].feed));
  CHECK(d.passes[0][1].feed == 300);
  CHECK(d.passes[0][1].line == 9);  // a continued statement is where it starts
  CHECK(d.passes[0][2].position == Eigen::Vector3d(2, 0, 1));
  REQUIRE(d.passes[1].size() == 4);
  CHECK(d.passes[1][1].position == Eigen::Vector3d(0, 0, 0.5 * 25.4));
  CHECK((d.passes[1][1].axis - Eigen::Vector3d(0, 0.6, 0.8)).norm() < 1e-15);
  // The axis is modal: a GOTO without one keeps the last.
  CHECK((d.passes[1][2].axis - Eigen::Vector3d(0, 0.6, 0.8)).norm() < 1e-15);
  CHECK(d.passes[1][2].feed == 600);
  CHECK(d.passes[1][3].feed == 254);  // 10 in/min, 1 in = 25.4 mm
  CHECK(d.has_axis);
}

TEST_CASE("CL reader: damaged files are refused at their line and column", "[cl][errors]") {
  struct Case {
    cl::Format format;
    const char* text;
    const char* expected;  // the start of "line:column: message"
  };
  const Case c = GENERATE(
      Case{cl::Format::Csv, "", "1:1: no header"},
      Case{cl::Format::Csv, "x,y,q\n",
           "1:5: column 3 of the header is not a name topomill knows: expected x, y, z"},
      Case{cl::Format::Csv, "x,y,x\n", "1:5: column 'x' appears twice"},
      Case{cl::Format::Csv, "x,y\n", "1:1: the header has no column 'z'"},
      Case{cl::Format::Csv, "x,y,z,i,j\n", "1:1: the header has some of i, j, k"},
      Case{cl::Format::Csv, "x,y,z\n0,0,0\n1,0,zero\n",
           "3:5: 'zero' is not a number: expected z (mm)"},
      Case{cl::Format::Csv, "x,y,z\n0,0,0\n1,0,nan\n", "3:5: 'nan' is not a number"},
      Case{cl::Format::Csv, "x,y,z\n0,0,0\n1,0,1e999\n", "3:5: '1e999' is not a number"},
      Case{cl::Format::Csv, "x,y,z\n0,0\n", "2:4: a row of 2 values: expected 3"},
      Case{cl::Format::Csv, "x,y,z\n0,0,0,4\n", "2:7: a row of 4 values: expected 3"},
      Case{cl::Format::Csv, "x,y,z\n0,0,0,\n", "2:7: a row of 4 values"},
      Case{cl::Format::Csv, "x,y,z,i,j,k\n0,0,0, 0,0,0\n", "2:8: the tool axis (i, j, k) is zero"},
      Case{cl::Format::Csv, "x,y,z,f\n0,0,0,-5\n", "2:7: a feed of -5 mm/min: expected more"},
      Case{cl::Format::Apt, "GOTO/1,2\n", "1:1: GOTO with 2 values: expected x, y, z"},
      Case{cl::Format::Apt, "  GOTO/1,2,3,4\n", "1:3: GOTO with 4 values"},
      Case{cl::Format::Apt, "GOTO/1,2,three\n", "1:10: 'three' is not a number: expected z"},
      Case{cl::Format::Apt, "GOTO/0,0,0\nCIRCLE/0,0,0,0,0,1,5\n",
           "2:1: CIRCLE is not a statement topomill follows"},
      Case{cl::Format::Apt, "CUTCOM/LEFT\n", "1:1: CUTCOM is not a statement"},
      // A file that is no CL data keeps its content out of the message (a scene from elsewhere
      // may name any file).
      Case{cl::Format::Apt, "root:secret-hash:0:0\n", "1:1: this is not a statement topomill"},
      Case{cl::Format::Csv, "root:secret-hash:0:0\n", "1:1: column 1 of the header is not a name"},
      Case{cl::Format::Apt, "FEDRAT/MMPM\n", "1:8: FEDRAT without a rate above 0"},
      Case{cl::Format::Apt, "FEDRAT/-3\n", "1:8: FEDRAT without a rate above 0"},
      Case{cl::Format::Apt, "UNITS/FEET\n", "1:7: UNITS/FEET: expected UNITS/MM or UNITS/INCHES"},
      Case{cl::Format::Apt, "TLAXIS/0,0\n", "1:1: TLAXIS with 2 values: expected i, j, k"},
      Case{cl::Format::Apt, "GOTO/0,0,0,0,0,0\n", "1:12: the tool axis (i, j, k) is zero"},
      Case{cl::Format::Apt, "GOTO/0,0,0\nGOTO/1,$\n", "2:1: the statement continues ('$') past"});
  INFO(c.text);
  const std::string got = refusal(c.text, c.format);
  INFO(got);
  CHECK(got.rfind(c.expected, 0) == 0);
  CHECK(got.find("secret") == std::string::npos);
}

TEST_CASE("CL reader: the format follows the file's name, else its first statement", "[cl]") {
  CHECK(cl::guess_format("a/b.csv", "GOTO/0,0,0") == cl::Format::Csv);
  CHECK(cl::guess_format("a/b.CLS", "x,y,z") == cl::Format::Apt);
  CHECK(cl::guess_format("a/b.apt", "") == cl::Format::Apt);
  CHECK(cl::guess_format("a/b", "\n  PARTNO/X\n") == cl::Format::Apt);
  CHECK(cl::guess_format("a/b", "$$ comment\nGOTO/0,0,0") == cl::Format::Apt);
  CHECK(cl::guess_format("a/b.data", "x,y,z\n") == cl::Format::Csv);
}
