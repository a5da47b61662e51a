// Springback of the machined surface (docs/model.md Eq. 29-31): plastic strain decaying
// exponentially below the surface, eps(z) = J1 exp(-J2 z), integrated over the plastic depth d.
#include <cmath>
#include <cstdio>

#include "topomill/deformation.hpp"
#include "topomill/error.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Eq. 30 as read from the paper's text (its minus signs and fraction bars are lost there):
//   J1 = cos a0 / (sqrt3 sin phi cos(phi - a0))
//   J2 = -ln(A) / ((n1 + 1) d),
//   A  = 1 - (n1 + 1) (Fx cos phi - Fy sin phi) (sqrt3 sin phi)^(n1+1) cos^n1(phi - a0)
//            / (K ae ap cos^n1 a0)
// and the displacement dd = (J1 / J2)(1 - exp(-J2 d)) (Eq. 31 as the integral of the strain;
// J1 d in the limit J2 -> 0). A <= 0 has no logarithm: refused with the values that made it.
class PlasticExponential : public Deformation {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("yield_strength", "Material yield strength K")
        .with_unit("MPa")
        .above(0)
        .is_required();
    s.add_number("hardening_exponent", "Hardening index n1 (Hollomon's n: 0 to 1 for metals)")
        .at_least(0)
        .at_most(1)
        .is_required();
    s.add_number("plastic_depth", "Depth d of plastic deformation")
        .with_unit("mm")
        .above(0)
        .is_required();
    s.add_number("rake_angle", "Tool rake angle a0 (Table 1's value is lost in the text)")
        .with_unit("deg")
        .above(-90)
        .below(90)
        .is_required();
    s.add_number("ae_ratio", "ae(theory) / ae(actual), giving phi = arcsin of it")
        .above(0)
        .at_most(1)
        .is_required();
    return s;
  }
  explicit PlasticExponential(const Params& p)
      : k_(p.number("yield_strength")),
        n1_(p.number("hardening_exponent")),
        d_(p.number("plastic_depth")),
        a0_(p.number("rake_angle") * M_PI / 180),
        phi_(std::asin(p.number("ae_ratio"))) {
    const double denom = std::sqrt(3.0) * std::sin(phi_) * std::cos(phi_ - a0_);
    if (!(std::abs(denom) > 1e-12))
      throw ParamError("rake_angle", "J1 of Eq. 30 is infinite: cos(phi - rake) = 0 with phi = " +
                                         format_number(phi_ * 180 / M_PI) + " deg");
    j1_ = std::cos(a0_) / denom;
  }

  double j1() const { return j1_; }

  Vec3 correction(const CuttingForce& f, const ToolGeometry&, const CutState& st) const override {
    const double fx = f.force.x(), fy = f.force.y();
    const double a = 1 - (n1_ + 1) * (fx * std::cos(phi_) - fy * std::sin(phi_)) *
                             std::pow(std::sqrt(3.0) * std::sin(phi_), n1_ + 1) *
                             std::pow(std::cos(phi_ - a0_), n1_) /
                             (k_ * st.stepover * st.depth_of_cut * std::pow(std::cos(a0_), n1_));
    if (!(a > 0)) {
      char msg[400];
      std::snprintf(
          msg, sizeof msg,
          "Eq. 30's logarithm has a non-positive argument %.4g (Fx = %.4g N, Fy = %.4g N, "
          "K = %.4g MPa, ae = %.4g mm, ap = %.4g mm, n1 = %.4g): the force is too large "
          "for this yield strength",
          a, fx, fy, k_, st.stepover, st.depth_of_cut, n1_);
      throw ParamError("yield_strength", msg);
    }
    const double j2 = -std::log(a) / ((n1_ + 1) * d_);
    const double dd = std::abs(j2 * d_) < 1e-12 ? j1_ * d_ : j1_ / j2 * (1 - std::exp(-j2 * d_));
    return {0.0, 0.0, dd};
  }

 private:
  double k_, n1_, d_, a0_, phi_, j1_ = 0;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("plastic_exponential", "0.1.0") {
  registrar.add<topomill::Deformation, topomill::plugins::PlasticExponential>(
      "plastic_exponential",
      "Surface springback from an exponential plastic strain profile "
      "(Eq. 29-31)");
}
