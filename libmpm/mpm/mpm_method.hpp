// The MPM behind the method seam, registered as "mpm" (mpm_method.cpp). Scenes reach it through
// build_method (method/method.hpp); these entry points serve callers that build the model
// themselves and inspect it after the run (tests, benchmarks).
#pragma once
#include <memory>

#include "libmpm/method/method.hpp"
#include "libmpm/method/run_loop.hpp"
#include "libmpm/mpm/model.hpp"

namespace cleave {

// A method that steps `m` in place (the caller keeps the model alive).
template <int Dim>
std::unique_ptr<Method<Dim>> make_mpm_method(Model<Dim>& m);

// Runs `m` with the one run loop (run_method).
template <int Dim>
RunSummary run_model(Model<Dim>& m, const RunOptions& opt) {
  return run_method<Dim>(*make_mpm_method<Dim>(m), opt);
}

}  // namespace cleave
