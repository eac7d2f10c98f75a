// Peridynamics behind the method seam, registered as "peridynamics" (pd_method.cpp). Scenes reach
// it through build_method (method/method.hpp); these entry points serve callers that build the
// system themselves and inspect it after the run (tests, benchmarks).
#pragma once
#include <memory>

#include "libmpm/method/method.hpp"
#include "libmpm/method/run_loop.hpp"
#include "libmpm/pd/pd_model.hpp"

namespace cleave::io {
struct PointSet;
}

namespace cleave::pd {

template <int Dim>
class PdSolver;

// A method that steps `m` in place (the caller keeps the system alive).
template <int Dim>
std::unique_ptr<Method<Dim>> make_pd_method(PdSystem<Dim>& m);

// Runs `m` with the one run loop (run_method).
template <int Dim>
RunSummary run_pd(PdSystem<Dim>& m, const RunOptions& opt) {
  return run_method<Dim>(*make_pd_method<Dim>(m), opt);
}

// One output frame of the current state (fields as in m.output.fields).
template <int Dim>
io::PointSet pd_point_set(const PdSystem<Dim>& m, const PdSolver<Dim>& s);

}  // namespace cleave::pd
