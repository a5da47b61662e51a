// How the row walk predicts a followed crossing at the next node (Root::ahead, root.hpp): by
// extrapolating a polynomial of degree 5 through the root's times at the row's last nodes, with
// the orders its history does not hold yet left out, and an order whose difference does not
// shrink left out too. Checked against sequences written here: powers of (n + 20) in the node's
// index n (their differences shrink with the order, as a smooth root's do on a fine grid) are
// exact up to degree 5 once five nodes are known, and off by exactly the sixth difference (6! b)
// for b (n + 20)^6, so an order dropped or added fails; a young root uses only what it holds
// (a parabola from its vertex shows an order let in early); a root whose differences grow is
// extrapolated by its parabola.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "tooth_passage/root.hpp"

using Root = topomill::plugins::Root;

namespace {

using Times = std::function<double(int)>;

// A root near 0.1 s moving by about a microsecond a node, as a crossing does: 0.1 + b (n + 20)^d
// with b set so that its first difference is 1e-6 at n = 0.
Times power(int d) {
  const double b = d == 0 ? 0.0 : 1e-6 / (std::pow(21.0, d) - std::pow(20.0, d));
  return [b, d](int n) { return 0.1 + b * std::pow(n + 20.0, d); };
}

// The prediction for node n + 1 made at node n, the root followed from node 0.
double predicted(const Times& t, int n) {
  Root r = Root::followed(t(0), nullptr, 400.0);
  for (int k = 1; k <= n; ++k) r = Root::followed(t(k), &r, 400.0);
  return r.ahead();
}

}  // namespace

TEST_CASE("a followed root is predicted exactly up to degree 5 once five nodes are known") {
  for (int d = 0; d <= 5; ++d) {
    const Times t = power(d);
    for (int n = 5; n < 12; ++n) {
      INFO("degree " << d << ", node " << n);
      CHECK(std::abs(predicted(t, n) - t(n + 1)) < 1e-15);
    }
  }
  // A sum of them too.
  const Times sum = [](int n) {
    double s = 0;
    for (int d = 1; d <= 5; ++d) s += power(d)(n) - 0.1;
    return 0.1 + s;
  };
  for (int n = 5; n < 12; ++n) CHECK(std::abs(predicted(sum, n) - sum(n + 1)) < 1e-15);
}

TEST_CASE("the prediction is of degree 5: a sixth power leaves its sixth difference") {
  const Times t = power(6);
  const double b = 1e-6 / (std::pow(21.0, 6) - std::pow(20.0, 6));
  for (int n = 5; n < 12; ++n) {
    INFO("node " << n);
    // The backward differences end at order 5: the error is the sixth, 6! b at unit steps
    // (3.3e-11 s here, far above round-off).
    CHECK(std::abs(predicted(t, n) - t(n + 1) + 720 * b) < 1e-15);
  }
}

TEST_CASE("a young root's prediction uses only the orders its history holds") {
  const Times cubic = power(3);
  // No history: where it is. One node before: its first move twice (the first move counts as
  // the bend too). Two: a parabola through three. Three and on: the cubic exactly.
  const double t0 = cubic(0), t1 = cubic(1), t2 = cubic(2);
  CHECK(Root::followed(t0, nullptr, 400.0).ahead() == t0);
  CHECK(std::abs(predicted(cubic, 1) - (t1 + 2 * (t1 - t0))) < 1e-15);
  CHECK(std::abs(predicted(cubic, 2) - (3 * t2 - 3 * t1 + t0)) < 1e-15);
  for (int n = 3; n < 8; ++n) CHECK(std::abs(predicted(cubic, n) - cubic(n + 1)) < 1e-15);
  // A parabola from its vertex, c n^2: at node 2 a third difference made from the first move
  // (counted as the bend: c) would be 2c - c = c, smaller than the bend 2c, so the shrink rule
  // would let it in (10c against the 9c due); the history must keep it out.
  const Times vertex = [](int n) { return 0.1 + 1e-6 * n * n; };
  CHECK(std::abs(predicted(vertex, 2) - vertex(3)) < 1e-15);
}

TEST_CASE("an order whose difference grows is left out: the grid is coarse for it") {
  // A parabola with a wobble of 1e-9 s at every other node: the second difference is the
  // wobble's 4e-9 (and the parabola's 2e-10), the third the wobble's 8e-9, so the prediction is
  // the parabola through the last three roots, not the quintic through six.
  const Times wobbly = [](int n) { return 0.1 + 1e-6 * n + 1e-10 * n * n + (n % 2 ? 1e-9 : 0.0); };
  for (int n = 5; n < 12; ++n) {
    INFO("node " << n);
    const double parabola = 3 * wobbly(n) - 3 * wobbly(n - 1) + wobbly(n - 2);
    CHECK(std::abs(predicted(wobbly, n) - parabola) < 1e-15);
  }
}
