// A centre crack of length 2a under remote tension sigma: Griffith/Irwin K_I = sigma sqrt(pi a) in an
// infinite plate; in a strip of width W Feddersen's secant correction sqrt(sec(pi a / W)) (within
// about 0.3 % of Isida's series for a/W < 0.3; docs/photoelasticity.md).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class CentreCrackKI final : public ClosedForm {
 public:
  std::string formula() const override {
    return "K_I = sigma sqrt(pi a) [sqrt(sec(pi a / W)) when a width W is given] (Griffith/Irwin, Feddersen)";
  }
  std::vector<Parameter> parameters() const override {
    return {{"stress", Quantity::Stress, "remote tension normal to the crack"},
            {"half_length", Quantity::Length, "half the crack length, a"},
            {"width", Quantity::Length, "the strip's width W (0: an infinite plate)", 0.0}};
  }
  std::string unit() const override { return "Pa m^1/2"; }
  double value(const Values& v, double) const override {
    const double a = v.at("half_length"), W = v.at("width");
    const double K = v.at("stress") * std::sqrt(M_PI * a);
    return W > 0 ? K / std::sqrt(std::cos(M_PI * a / W)) : K;
  }
};

const bool registered =
    ClosedFormRegistry::instance().add("centre_crack_KI", [] { return std::make_unique<CentreCrackKI>(); });

}  // namespace
}  // namespace cleave::reference
