// topomill study: a resolution ladder per evaluator with its cost, against the finest run.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/csv_table.hpp"
#include "support/run_command.hpp"

TEST_CASE("study: Sa converges down the ladder and nodes grow as 1/spacing^2", "[batch][study]") {
  const std::string out = testing::temp_dir("study");
  const auto r = testing::run_topomill(
      "study tests/stability/base.toml --evaluator tooth_passage --spacing 0.005,0.02,0.01 "
      "--jobs 2 --out '" +
      out + "'");
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = testing::read_csv_rows(out + "/study.csv");
  REQUIRE(rows.size() == 4);
  const auto& h = rows[0];
  auto col = [&](const std::string& name) { return testing::column(h, name); };
  // Coarse to fine, whatever order the spacings were given in; the finest is the reference.
  CHECK(rows[1][col("spacing_mm")] == "0.02");
  CHECK(rows[3][col("spacing_mm")] == "0.005");
  CHECK(rows[3][col("status")] == "reference");
  CHECK(rows[3][col("dSa_percent")] == "0");
  const double e20 = std::abs(std::stod(rows[1][col("dSa_percent")]));
  const double e10 = std::abs(std::stod(rows[2][col("dSa_percent")]));
  CHECK(e10 < e20);
  // 0.1 mm patch: 6, 11 and 21 nodes a side.
  CHECK(rows[1][col("nodes")] == "36");
  CHECK(rows[2][col("nodes")] == "121");
  CHECK(rows[3][col("nodes")] == "441");
  CHECK(testing::read_file(out + "/study.png").substr(1, 3) == "PNG");
}

TEST_CASE("study refuses a bad ladder or reference before running", "[batch][study][errors]") {
  const std::string out = testing::temp_dir("study_refused");
  auto r = testing::run_topomill("study tests/stability/base.toml --spacing 0.01,-2 --out '" + out +
                                 "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("key '--spacing': '-2' is not a positive spacing") != std::string::npos);
  r = testing::run_topomill(
      "study tests/stability/base.toml --evaluator zmap --reference "
      "tooth_passage --out '" +
      out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("'tooth_passage' is not among the studied evaluators") != std::string::npos);
  r = testing::run_topomill("study tests/stability/base.toml --knob zmap.time_step=x --out '" +
                            out + "'");
  CHECK(r.exit_code == 2);
  r = testing::run_topomill(
      "study tests/stability/base.toml --evaluator tooth_passage --knob "
      "zmap.time_step_fraction=0.5 --out '" +
      out + "'");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("'zmap' is not among the studied evaluators") != std::string::npos);
}
