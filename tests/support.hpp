// Helpers shared by the validation tests: scenes built in code, models stepped directly, and the
// error a scene is refused with.
#pragma once
#include <gtest/gtest.h>

#include <exception>
#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "libmpm/mpm/mpm_step.hpp"

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

// The DCB's load-point opening (data/scenes/dcb_crack.json): the mean y displacement of the first
// particle column (x0 = 0.5 mm) of the upper arm minus that of the lower arm.
inline double dcb_load_point_opening(const Particles<2>& P) {
  double top = 0, bottom = 0;
  int nt = 0, nb = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec<2> x0 = P.x[p] - P.u[p];
    if (x0.x() > 1e-3) continue;
    (x0.y() > 0 ? top : bottom) += P.u[p].y();
    ++(x0.y() > 0 ? nt : nb);
  }
  return top / nt - bottom / nb;
}

// The SceneError that f() throws; fails the test when it throws none or another exception.
template <class F>
SceneError error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SceneError, got: " << e.what();
    return SceneError("(other)", e.what());
  }
  ADD_FAILURE() << "expected a SceneError, got none";
  return SceneError("(none)", "");
}

}  // namespace cleave::test
