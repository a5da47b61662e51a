// The stability lobes as a picture: critical depth against spindle speed, the unstable region
// above the boundary shaded red and the stable one below green, the boundary drawn by its kind
// (Hopf, flip), and the scene's operating point marked.
#pragma once

#include <string>
#include <vector>

namespace topomill {

struct LobeCurve {
  std::vector<double> rpm, depth;  // depth NaN: stable up to depth_max
  std::vector<bool> flip;          // per speed: the boundary is a flip (else Hopf)
  double depth_max = 0;
  double operating_rpm = 0, operating_depth = 0;
  bool operating_stable = true;
  std::string title;
};

void write_lobes_chart(const std::string& path, const LobeCurve& c);

}  // namespace topomill
