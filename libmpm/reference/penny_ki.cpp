// A penny-shaped crack of radius a in an infinite solid under remote tension sigma normal to it:
// K_I = 2 sigma sqrt(a / pi) all along the front (Sneddon; validation.md section 4).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class PennyKI final : public ClosedForm {
 public:
  std::string formula() const override { return "K_I = 2 sigma sqrt(a / pi) (Sneddon's penny crack)"; }
  std::vector<Parameter> parameters() const override {
    return {{"stress", Quantity::Stress, "remote tension normal to the crack"},
            {"radius", Quantity::Length, "the crack's radius a"}};
  }
  std::string unit() const override { return "Pa m^1/2"; }
  double value(const Values& v, double) const override { return 2 * v.at("stress") * std::sqrt(v.at("radius") / M_PI); }
};

const bool registered = ClosedFormRegistry::instance().add("penny_KI", [] { return std::make_unique<PennyKI>(); });

}  // namespace
}  // namespace cleave::reference
