// tooth_passage's range table (the correction's extent and speed over a span) against a scan.
#include <array>
#include <catch2/catch.hpp>
#include <random>

#include "tooth_passage/range_table.hpp"

TEST_CASE("range table: min and max of every run equal a scan", "[fast]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1, 1);
  for (std::size_t n : {1, 2, 3, 4, 5, 7, 8, 9, 31, 64, 100, 1000}) {
    std::vector<double> v(n);
    for (double& x : v) x = value(rng);
    // One component alone, and three that share the table (the middle one the values, the
    // others their negatives and squares: each component's extremes its own).
    auto at = [&](std::size_t k) { return std::array<double, 1>{v[k]}; };
    auto at3 = [&](std::size_t k) { return std::array<double, 3>{-v[k], v[k], v[k] * v[k]}; };
    const topomill::plugins::RangeTable<1> table(n, at);
    const topomill::plugins::RangeTable<3> table3(n, at3);
    for (int q = 0; q < 2000; ++q) {
      std::size_t i = rng() % n, j = rng() % n;
      if (q == 0) i = 0, j = n - 1;  // the whole sequence
      if (i > j) std::swap(i, j);
      double lo = INFINITY, hi = -INFINITY, sq_lo = INFINITY, sq_hi = -INFINITY;
      for (std::size_t k = i; k <= j; ++k) {
        lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
        sq_lo = std::min(sq_lo, v[k] * v[k]), sq_hi = std::max(sq_hi, v[k] * v[k]);
      }
      const auto [tlo, thi] = table.over(i, j, at);
      const auto [lo3, hi3] = table3.over(i, j, at3);
      INFO("n " << n << ", [" << i << ", " << j << "]");
      REQUIRE(tlo[0] == lo);
      REQUIRE(thi[0] == hi);
      REQUIRE(lo3[0] == -hi);
      REQUIRE(hi3[0] == -lo);
      REQUIRE(lo3[1] == lo);
      REQUIRE(hi3[1] == hi);
      REQUIRE(lo3[2] == sq_lo);
      REQUIRE(hi3[2] == sq_hi);
    }
  }
}
