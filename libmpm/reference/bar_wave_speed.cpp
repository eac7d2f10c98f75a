// The speed of a longitudinal wave in a thin bar, c = sqrt(E / rho) (validation.md section 1).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class BarWaveSpeed final : public ClosedForm {
 public:
  std::string formula() const override { return "c = sqrt(E / rho) (1D bar; validation.md section 1)"; }
  std::vector<Parameter> parameters() const override {
    return {{"E", Quantity::Stress, "Young's modulus"}, {"density", Quantity::Density, "density"}};
  }
  std::string unit() const override { return "m/s"; }
  double value(const Values& v, double) const override { return std::sqrt(v.at("E") / v.at("density")); }
};

const bool registered =
    ClosedFormRegistry::instance().add("bar_wave_speed", [] { return std::make_unique<BarWaveSpeed>(); });

}  // namespace
}  // namespace cleave::reference
