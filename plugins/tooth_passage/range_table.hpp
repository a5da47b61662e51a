// The smallest and largest of any run values[i .. j] of a fixed sequence of K-vectors (each
// component on its own), read through `at(k)`: the extremes of each block of kBlock values in a
// bottom-up segment tree, a query reading the tree for the whole blocks inside and the values
// themselves at its two ragged ends: O(kBlock + log n) a query, 4 K n / kBlock doubles. The
// correction is sampled 64 times a tooth period, and the bounds of a span (PassageGeometry::span)
// ask for its extent and speed over every piece cut near the tool's axis: a scan over the samples
// cost as much as the rest of the search there. The components that are asked together (the
// correction's x, y and z and its speeds in plan and along z) share one table, so that a query
// walks the tree once for all (a piece with correction knots inside would otherwise ask for eight
// walks). Blocks of 4 make 40 bytes a correction sample for the table of a pass (budgeted in
// resources.cpp); a tree over single samples takes four times that, blocks of 16 are slower.
// The ragged ends are most of a query's cost: crossings_in cuts its pieces where they keep to
// the blocks (PassageGeometry::split_time).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace topomill::plugins {

template <std::size_t K>
class RangeTable {
 public:
  static constexpr std::size_t kBlock = 4;
  using Values = std::array<double, K>;

  RangeTable() = default;
  template <class At>
  RangeTable(std::size_t n, At at) : n_(n), blocks_((n + kBlock - 1) / kBlock) {
    lo_.assign(2 * blocks_, filled(INFINITY)), hi_.assign(2 * blocks_, filled(-INFINITY));
    for (std::size_t k = 0; k < n; ++k)
      take(lo_[blocks_ + k / kBlock], hi_[blocks_ + k / kBlock], at(k));
    for (std::size_t b = blocks_; b-- > 1;) {
      lo_[b] = lo_[2 * b], hi_[b] = hi_[2 * b];
      take(lo_[b], hi_[b], lo_[2 * b + 1], hi_[2 * b + 1]);
    }
  }
  bool empty() const { return n_ == 0; }

  // {min, max} over values[i .. j] (i <= j < n, inclusive), with the same `at` as built.
  template <class At>
  std::pair<Values, Values> over(std::size_t i, std::size_t j, At at) const {
    Values lo = filled(INFINITY), hi = filled(-INFINITY);
    auto scan = [&](std::size_t a, std::size_t b) {  // [a, b)
      for (std::size_t k = a; k < b; ++k) take(lo, hi, at(k));
    };
    const std::size_t b0 = (i + kBlock - 1) / kBlock, b1 = (j + 1) / kBlock;  // whole: [b0, b1)
    if (b0 >= b1) {
      scan(i, j + 1);
      return {lo, hi};
    }
    scan(i, b0 * kBlock), scan(b1 * kBlock, j + 1);
    for (std::size_t l = b0 + blocks_, r = b1 + blocks_; l < r; l /= 2, r /= 2) {
      if (l & 1) take(lo, hi, lo_[l], hi_[l]), ++l;
      if (r & 1) --r, take(lo, hi, lo_[r], hi_[r]);
    }
    return {lo, hi};
  }

 private:
  static Values filled(double x) {
    Values v;
    v.fill(x);
    return v;
  }
  static void take(Values& lo, Values& hi, const Values& v) { take(lo, hi, v, v); }
  static void take(Values& lo, Values& hi, const Values& vlo, const Values& vhi) {
    for (std::size_t c = 0; c < K; ++c)
      lo[c] = std::min(lo[c], vlo[c]), hi[c] = std::max(hi[c], vhi[c]);
  }

  std::size_t n_ = 0, blocks_ = 0;
  std::vector<Values> lo_, hi_;  // tree node b covers 2b and 2b + 1; the blocks from blocks_ on
};

}  // namespace topomill::plugins
