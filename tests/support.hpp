// Helpers shared by the validation tests: scenes built in code, models stepped directly.
#pragma once
#include <nlohmann/json.hpp>

#include "libmpm/scene/scene.hpp"
#include "libmpm/solver/mpm_step.hpp"

namespace cleave::test {

using nlohmann::json;

inline json material(const std::string& name, double E, double nu, double rho) {
  return {{"name", name}, {"type", "linear_elastic"}, {"E", E}, {"nu", nu}, {"density", rho}};
}

// Steps a model n times; fails the calling test if a step reports a problem.
template <int Dim>
inline StepProblem advance(Stepper<Dim>& s, long n) {
  for (long i = 0; i < n; ++i) {
    StepProblem p = s.step();
    if (p) return p;
  }
  return {};
}

}  // namespace cleave::test
