// The energy release rate of a double cantilever beam by beam theory with shear (validation.md
// section 3): G_I = 12 P^2 a^2 / (E b^2 h^3) + 6 P^2 / (5 G b^2 h), arm height h, width b, crack
// length a, end force P on each arm; root rotation by a -> a + chi h (chi about 0.64, Kanninen).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class DcbEnergyRelease final : public ClosedForm {
 public:
  std::string formula() const override {
    return "G_I = 12 P^2 (a + chi h)^2 / (E b^2 h^3) + 6 P^2 / (5 G b^2 h) (beam theory; validation.md section 3)";
  }
  std::vector<Parameter> parameters() const override {
    return {{"force", Quantity::Force, "the end force P on each arm"},
            {"crack_length", Quantity::Length, "the crack length a from the loaded end"},
            {"arm_height", Quantity::Length, "the height h of each arm"},
            {"thickness", Quantity::Length, "the width b"},
            {"E", Quantity::Stress, "Young's modulus"},
            {"nu", std::nullopt, "Poisson's ratio"},
            {"chi", std::nullopt, "root rotation factor (0: built-in arms; about 0.64 after Kanninen)", 0.0}};
  }
  std::string unit() const override { return "J/m^2"; }
  double value(const Values& v, double) const override {
    const double P = v.at("force"), h = v.at("arm_height"), b = v.at("thickness"), E = v.at("E");
    const double a = v.at("crack_length") + v.at("chi") * h, G = E / (2 * (1 + v.at("nu")));
    return 12 * P * P * a * a / (E * b * b * h * h * h) + 6 * P * P / (5 * G * b * b * h);
  }
};

const bool registered =
    ClosedFormRegistry::instance().add("dcb_G", [] { return std::make_unique<DcbEnergyRelease>(); });

}  // namespace
}  // namespace cleave::reference
