// What both modal dynamics models share: the modes table (Table 4 form), per-axis modal
// superposition, and the time step choice.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "topomill/dynamics_model.hpp"
#include "topomill/error.hpp"
#include "topomill/params.hpp"

namespace topomill::plugins {

struct Mode {
  int axis;           // 0 x, 1 y, 2 z
  double omega;       // rad/s
  double xi;          // damping ratio
  double k;           // N/m
  std::string label;  // "mode 2 (y, 800 Hz)" for messages
};

class Modal : public DynamicsModel {
 public:
  static Schema base_schema() {
    Schema mode;
    mode.add_choice("axis", {"x", "y", "z"}, "Axis the mode acts along").is_required();
    mode.add_number("frequency", "Natural frequency f").with_unit("Hz").above(0).is_required();
    mode.add_number("damping", "Damping ratio xi").at_least(0).below(1).is_required();
    mode.add_number("stiffness", "Modal stiffness k").with_unit("N/m").above(0).is_required();
    Schema s;
    s.add_table_array("modes", mode, "Modes, any number per axis; the axis response is their sum")
        .is_required();
    s.add_number("time_step",
                 "Step of forces and response; 0 = a 40th of the fastest mode's period")
        .with_unit("s")
        .at_least(0)
        .with_default(0.0);
    return s;
  }

  explicit Modal(const Params& p) : time_step_(p.number("time_step")) {
    const auto& tables = p.tables("modes");
    if (tables.empty()) throw ParamError("modes", "at least one mode is needed");
    for (std::size_t i = 0; i < tables.size(); ++i) {
      const Params& t = tables[i];
      const std::string axis = t.string("axis");
      const double f = t.number("frequency");
      char label[64];
      std::snprintf(label, sizeof label, "mode %zu (%s, %g Hz)", i + 1, axis.c_str(), f);
      const int index = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
      modes_.push_back({index, 2 * M_PI * f, t.number("damping"), t.number("stiffness"), label});
    }
  }

  double suggested_step() const override {
    if (time_step_ > 0) return time_step_;
    double fastest = 0;
    for (const auto& m : modes_) fastest = std::max(fastest, m.omega);
    return 2 * M_PI / fastest / 40;
  }

  std::vector<ModalMode> modes() const override {
    std::vector<ModalMode> out;
    for (const auto& m : modes_) out.push_back({m.axis, m.omega, m.xi, m.k});
    return out;
  }

  // Displacement in mm: the sum over modes of each mode's response (m) to its axis' force.
  std::vector<Vec3> respond(const std::vector<Vec3>& force, double dt) const override {
    std::vector<Vec3> out(force.size(), Vec3::Zero());
    std::vector<double> f(force.size()), q;
    for (const auto& m : modes_) {
      for (std::size_t i = 0; i < force.size(); ++i) f[i] = force[i][m.axis];
      integrate(m, f, dt, q);
      for (std::size_t i = 0; i < force.size(); ++i) out[i][m.axis] += 1e3 * q[i];
    }
    return out;
  }

 protected:
  // Response q (m) of one mode, from rest, to the force f (N) held constant over each step.
  virtual void integrate(const Mode& m, const std::vector<double>& f, double dt,
                         std::vector<double>& q) const = 0;

  std::vector<Mode> modes_;
  double time_step_;
};

}  // namespace topomill::plugins
