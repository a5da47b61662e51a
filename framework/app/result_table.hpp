// A table of results (sweep, ablation, study) written as CSV and as Markdown, both atomically.
#pragma once

#include <string>
#include <vector>

#include "case_runner.hpp"

namespace topomill::cli {

struct ResultTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  void write_csv(const std::string& path) const;       // RFC 4180 quoting
  void write_markdown(const std::string& path) const;  // a pipe table
  std::string markdown() const;
};

// "%.4g", or "" for a non-finite value.
std::string cell(double v);

// The value of parameter `name` (Sa, Sq, ...) of a result, NaN when the case failed.
double parameter(const CaseResult& r, const std::string& name);

// "evaluate 1.2 s, force 0.3 s" from a result's stages.
std::string stage_list(const CaseResult& r);

}  // namespace topomill::cli
