// The static tip deflection of a cantilever of length L, height h and thickness b under an end force
// P: Euler-Bernoulli P L^3 / (3 E I), I = b h^3 / 12, plus Timoshenko's shear part P L / (k G A),
// k = 5/6 for a rectangle (short, thick beams; Timoshenko & Goodier).
#include <cmath>

#include "libmpm/reference/closed_form.hpp"

namespace cleave::reference {
namespace {

class CantileverDeflection final : public ClosedForm {
 public:
  std::string formula() const override {
    return "delta = P L^3 / (3 E I) + P L / (k G b h), I = b h^3 / 12, k = 5/6 (Timoshenko)";
  }
  std::vector<Parameter> parameters() const override {
    return {{"force", Quantity::Force, "the end force P"},
            {"length", Quantity::Length, "the free length L"},
            {"height", Quantity::Length, "the height h (in the plane of bending)"},
            {"thickness", Quantity::Length, "the thickness b"},
            {"E", Quantity::Stress, "Young's modulus"},
            {"nu", std::nullopt, "Poisson's ratio (shear part)"}};
  }
  std::string unit() const override { return "m"; }
  double value(const Values& v, double) const override {
    const double P = v.at("force"), L = v.at("length"), h = v.at("height"), b = v.at("thickness"), E = v.at("E");
    const double G = E / (2 * (1 + v.at("nu"))), I = b * h * h * h / 12;
    return P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * b * h);
  }
};

const bool registered = ClosedFormRegistry::instance().add("cantilever_deflection",
                                                           [] { return std::make_unique<CantileverDeflection>(); });

}  // namespace
}  // namespace cleave::reference
