#include "libmpm/pd/constants.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cleave::pd {

namespace {
void require_positive(double v, const char* name) {
  if (!(std::isfinite(v) && v > 0.0))
    throw std::invalid_argument(std::string("pd_constants: ") + name + " must be positive and finite");
}
}  // namespace

PdConstants pd_constants(PdModel model, double E_or_K, double G0, double delta, double thickness) {
  constexpr double pi = std::numbers::pi;
  require_positive(E_or_K, model == PdModel::ThreeD ? "bulk modulus K" : "Young's modulus E");
  require_positive(G0, "fracture energy G0");
  require_positive(delta, "horizon delta");
  if (model != PdModel::ThreeD) require_positive(thickness, "thickness");
  const double d3 = delta * delta * delta;
  switch (model) {
    case PdModel::PlaneStress: {
      const double E = E_or_K;
      return {9.0 * E / (pi * thickness * d3), std::sqrt(4.0 * pi * G0 / (9.0 * E * delta)), 1.0 / 3.0};
    }
    case PdModel::PlaneStrain: {
      const double E = E_or_K;
      return {48.0 * E / (5.0 * pi * thickness * d3), std::sqrt(5.0 * pi * G0 / (12.0 * E * delta)), 0.25};
    }
    case PdModel::ThreeD: {
      const double K = E_or_K;
      return {18.0 * K / (pi * d3 * delta), std::sqrt(5.0 * G0 / (9.0 * K * delta)), 0.25};
    }
  }
  throw std::invalid_argument("pd_constants: unknown model");
}

}  // namespace cleave::pd
