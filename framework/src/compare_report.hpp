// The files `topomill compare` writes: compare.json (every number in full precision),
// compare.md, the difference map (difference.x3p, difference.png), the two surfaces side by side
// (surfaces.png), and the areal autocorrelation and power spectrum of each (acf_*.png,
// psd_*.png); and the console's one-screen summary.
#pragma once

#include <string>

#include "compare.hpp"

namespace topomill {

struct CompareInputs {
  std::string sim_file, meas_file, processing;
};

struct CompareReport {
  std::string json, markdown, summary;
};

// All of it staged beside `dir` and moved into place when complete: a failure leaves no part of
// it. An existing `dir` is replaced only when it holds an earlier compare's output (compare.json);
// any other is refused (InputError naming --out).
CompareReport write_compare_report(const std::string& dir, const Comparison& c,
                                   const CompareInputs& inputs);

}  // namespace topomill
