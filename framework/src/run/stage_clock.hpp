// Times a run's stages: each stage's wall time is recorded under its name when it ends, also when
// it throws.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "log.hpp"

namespace topomill {

struct StageTime {
  std::string name;
  double seconds = 0;
};

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& out) : out_(out) {}
  template <class F>
  auto run(const std::string& name, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    struct Record {
      std::vector<StageTime>& out;
      std::string name;
      std::chrono::steady_clock::time_point t0;
      ~Record() {
        out.push_back(
            {name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
        log_debug("stage '" + name + "': " + std::to_string(out.back().seconds) + " s");
      }
    } record{out_, name, t0};
    return f();
  }

 private:
  std::vector<StageTime>& out_;
};

}  // namespace topomill
