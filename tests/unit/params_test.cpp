// The parameter schema: what it promises in messages, and its range checks at the bounds.
#include <catch2/catch.hpp>

#include "topomill/params.hpp"

using topomill::ParamSpec;
using topomill::Schema;

TEST_CASE("range checks honour inclusive and exclusive bounds", "[params]") {
  Schema s;
  ParamSpec& open = s.add_number("a", "doc").above(0).below(1);
  CHECK(open.range_violation(0.0) == "> 0 and < 1");
  CHECK(open.range_violation(1.0) == "> 0 and < 1");
  CHECK(open.range_violation(0.5).empty());
  ParamSpec& closed = s.add_number("b", "doc").at_least(0).at_most(1);
  CHECK(closed.range_violation(0.0).empty());
  CHECK(closed.range_violation(1.0).empty());
  CHECK(closed.range_violation(1.0000001) == ">= 0 and <= 1");
  ParamSpec& free = s.add_number("c", "doc");
  CHECK(free.range_violation(1e300).empty());
  CHECK(free.range_violation(std::numeric_limits<double>::infinity()) == "finite");
  CHECK(free.range_violation(std::nan("")) == "finite");
}

TEST_CASE("expectations read as the scene reference states them", "[params]") {
  Schema s;
  CHECK(s.add_number("r", "d").with_unit("mm").above(0).expectation() == "a number > 0 (mm)");
  CHECK(s.add_integer("n", "d").at_least(1).expectation() == "an integer >= 1");
  CHECK(s.add_choice("dir", {"cw", "ccw"}, "d").expectation() == "one of cw, ccw");
  CHECK(s.add_number_array("size", "d").with_length(2).above(0).expectation() ==
        "an array of 2 numbers, each > 0");
  CHECK(s.names() == std::vector<std::string>{"r", "n", "dir", "size"});
  CHECK(s.find("dir")->type == topomill::ParamType::Choice);
  CHECK(s.find("nope") == nullptr);
}

TEST_CASE("params convert integers to numbers and know where each value came from", "[params]") {
  topomill::Params p;
  p.set_path("tool");
  p.set_table_where({"scene.toml", 3, 1});
  p.set("teeth", std::int64_t{4}, {"scene.toml", 5, 9});
  p.set("radius", 5.0);
  CHECK(p.number("teeth") == 4.0);
  CHECK(p.integer("teeth") == 4);
  CHECK(p.where("teeth").str() == "scene.toml:5:9");
  CHECK(p.where("radius").str() == "scene.toml:3:1");  // a default: the table's position
  CHECK_THROWS_WITH(p.number("missing"), Catch::Contains("'tool.missing' was read but is not"));
  CHECK_THROWS(p.string("radius"));
}
