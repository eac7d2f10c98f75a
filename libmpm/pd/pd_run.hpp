// The peridynamic run: the MPM runner's contract (solver/run.hpp) for "method": "peridynamics".
// Writes into OUT: particles.pvd + particles_NNNNNN.vtu (displacement, velocity, damage, stress
// estimated from bond forces, ...), global.csv (energies, works, broken bonds), crack_tips.csv
// (time, branch, x, y[, z], speed), checkpoint.bin at every frame and run.json (status; 2D runs also
// record the first detected branching).
#pragma once
#include "libmpm/pd/pd_model.hpp"
#include "libmpm/solver/run.hpp"

namespace cleave::io {
struct PointSet;
}

namespace cleave::pd {

template <int Dim>
class PdSolver;

// Throws RunAborted (after writing the last state) on a non-finite or blown-up energy.
template <int Dim>
RunSummary run_pd(PdSystem<Dim>& m, const RunOptions& opt);

// One output frame of the current state (fields as in m.output.fields).
template <int Dim>
io::PointSet pd_point_set(const PdSystem<Dim>& m, const PdSolver<Dim>& s);

}  // namespace cleave::pd
