// The same scene gives identical bits with 1, 2 and 4 threads and from one run to the next
// (issue #9), for both evaluators, with the ideal path and with every effect.
#include <catch2/catch.hpp>
#include <cstring>

#include "support/run_command.hpp"
#include "support/scenes.hpp"

namespace {

bool same_bits(const topomill::HeightMap& a, const topomill::HeightMap& b) {
  return a.grid.nx == b.grid.nx && a.grid.ny == b.grid.ny && a.z.size() == b.z.size() &&
         std::memcmp(a.z.data(), b.z.data(), a.z.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("identical bits on 1, 2 and 4 threads and across runs", "[stability][threads]") {
  const std::string base = testing::read_file(testing::source_dir() + "/tests/stability/base.toml");
  const std::vector<std::string> all_effects = {"vibration.enabled=true", "deflection.enabled=true",
                                                "springback.enabled=true"};
  for (const std::string evaluator : {"tooth_passage", "zmap"}) {
    for (const bool effects : {false, true}) {
      DYNAMIC_SECTION(evaluator << (effects ? ", all effects" : ", ideal")) {
        // The Z-map's cost grows as 1/spacing^2: a coarser grid keeps it to seconds.
        const bool zmap = evaluator == "zmap";
        std::vector<std::string> set = {"evaluator.plugin=\"" + evaluator + "\"",
                                        zmap ? "region.spacing=0.02" : "region.spacing=0.005"};
        if (effects) set.insert(set.end(), all_effects.begin(), all_effects.end());
        const auto one = testing::run_scene(base, set, 1);
        REQUIRE(one.raw.z.size() >= (zmap ? 25u : 400u));
        for (const unsigned threads : {1u, 2u, 4u}) {
          const auto other = testing::run_scene(base, set, threads);
          INFO(threads << " threads");
          CHECK(same_bits(one.raw, other.raw));
          CHECK(same_bits(one.residual, other.residual));
          CHECK(one.roughness.Sa == other.roughness.Sa);
        }
      }
    }
  }
}
