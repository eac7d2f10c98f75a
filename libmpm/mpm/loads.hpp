// Loads and grid conditions a scene can declare, already resolved against the particles and grid.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "libmpm/core/types.hpp"

namespace cleave {

// Time dependence of a load: constant from t = 0, or a linear ramp to full value at rise_time.
struct TimeFunction {
  double rise_time = 0.0;
  double operator()(double t) const { return rise_time > 0.0 && t < rise_time ? t / rise_time : 1.0; }
};

// A traction on particle faces: force = traction * face area, spread to the grid with the shape
// functions evaluated on the loaded face (consistent with the uGIMP integration of internal force).
template <int Dim>
struct TractionLoad {
  std::string name;
  Vec<Dim> traction = Vec<Dim>::Zero();  // Pa
  int axis = 0;                           // face normal axis
  int side = 1;                           // +1 or -1
  TimeFunction time_function;
  std::vector<int32_t> particles;
  std::vector<double> face_area;  // m^2 per particle
};

// Prescribed nodal velocity components (a fixed support is velocity 0).
template <int Dim>
struct VelocityCondition {
  std::vector<int64_t> nodes;
  std::array<bool, Dim> fixed{};
  Vec<Dim> velocity = Vec<Dim>::Zero();
};

}  // namespace cleave
