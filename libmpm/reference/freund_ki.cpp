// Freund's semi-infinite crack whose faces are loaded suddenly by a pressure p at t0 (plane strain,
// valid until the first reflected wave reaches the tip), validation.md section 3:
// K_I(t) = (2p / (1 - nu)) sqrt(c_d (t - t0) (1 - 2 nu) / pi).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class FreundKI final : public ClosedForm {
 public:
  std::string formula() const override {
    return "K_I(t) = 2p/(1-nu) sqrt(c_d (t-t0) (1-2nu)/pi), plane strain (Freund; validation.md section 3)";
  }
  std::vector<Parameter> parameters() const override {
    return {{"pressure", Quantity::Stress, "the pressure on the crack faces from t0"},
            {"E", Quantity::Stress, "Young's modulus"},
            {"nu", std::nullopt, "Poisson's ratio"},
            {"density", Quantity::Density, "density"},
            {"onset", Quantity::Time, "the time t0 the load reaches the crack faces", 0.0}};
  }
  std::string unit() const override { return "Pa m^1/2"; }
  double value(const Values& v, double t) const override {
    const double nu = v.at("nu"), tau = t - v.at("onset");
    if (tau <= 0) return 0.0;
    const double cd = dilatational_speed(v.at("E"), nu, v.at("density"), false);
    return 2 * v.at("pressure") / (1 - nu) * std::sqrt(cd * tau * (1 - 2 * nu) / M_PI);
  }
};

const bool registered = ClosedFormRegistry::instance().add("freund_KI", [] { return std::make_unique<FreundKI>(); });

}  // namespace
}  // namespace cleave::reference
