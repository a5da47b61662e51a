// tooth_passage's range table (the correction's extent and speed over a span) against a scan.
#include <catch2/catch.hpp>
#include <random>

#include "tooth_passage/range_table.hpp"

TEST_CASE("range table: min and max of every run equal a scan", "[fast]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1, 1);
  for (std::size_t n : {1, 2, 3, 4, 5, 7, 8, 9, 31, 64, 100, 1000}) {
    std::vector<double> v(n);
    for (double& x : v) x = value(rng);
    auto at = [&](std::size_t k) { return v[k]; };
    const topomill::plugins::RangeTable table(n, at);
    for (int q = 0; q < 2000; ++q) {
      std::size_t i = rng() % n, j = rng() % n;
      if (q == 0) i = 0, j = n - 1;  // the whole sequence
      if (i > j) std::swap(i, j);
      double lo = INFINITY, hi = -INFINITY;
      for (std::size_t k = i; k <= j; ++k) lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
      const auto [tlo, thi] = table.over(i, j, at);
      INFO("n " << n << ", [" << i << ", " << j << "]");
      REQUIRE(tlo == lo);
      REQUIRE(thi == hi);
    }
  }
}
