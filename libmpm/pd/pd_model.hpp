// A bond-based peridynamic model built from a scene ("method": "peridynamics"): lattice points of
// every body, their bonds, materials, loads and settings, all SI. docs/peridynamics.md describes it.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "libmpm/core/run_settings.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/pd/bonds.hpp"
#include "libmpm/pd/constants.hpp"

namespace cleave::pd {

struct PdMaterial {
  std::string name;
  double E = 0, nu_given = -1, density = 0, G0 = 0;
  PdConstants k{};  // micromodulus, critical stretch, implied nu
};

// Points as a structure of arrays (one entry per lattice point).
template <int Dim>
struct PdPoints {
  std::vector<Vec<Dim>> x0;     // reference position
  std::vector<Vec<Dim>> u;      // displacement
  std::vector<Vec<Dim>> v;      // velocity
  std::vector<Vec<Dim>> a;      // acceleration at the current time (velocity-Verlet needs it)
  std::vector<Vec<Dim>> b;      // external force density (N/m^3) at the current time
  std::vector<double> volume;   // V = dx^Dim (times thickness in 2D)
  std::vector<double> mass;     // rho V
  std::vector<int32_t> material;
  std::vector<int32_t> body;
  std::vector<uint8_t> no_fail;  // 1: bonds of this point never break
  std::vector<uint8_t> fixed;    // bit d: velocity component d prescribed
  std::vector<Vec<Dim>> v_fixed;  // prescribed velocity components
  std::size_t size() const { return x0.size(); }
  void resize(std::size_t n) {
    x0.resize(n), u.resize(n), v.resize(n), a.resize(n), b.resize(n), volume.resize(n), mass.resize(n);
    material.resize(n), body.resize(n), no_fail.resize(n), fixed.resize(n), v_fixed.resize(n);
  }
};

// Bonds of each point, both directions (every bond appears once in the list of each end point):
// point p owns entries [offset[p], offset[p+1]), sorted by partner. Both copies of a bond see the
// same stretch (the same doubles, negated) so they break in the same step; each point sums only its
// own entries, so the force loop runs over points in parallel with no atomics and no scatter, and
// the result is the same for any thread count. Twice the storage of a once-per-bond list, in return
// for one pass and no force buffer (docs/peridynamics.md, "Data layout").
template <int Dim>
struct PdNeighbours {
  std::vector<int64_t> offset;    // n_points + 1
  std::vector<int32_t> partner;   // j
  std::vector<double> r0;         // |xi|
  std::vector<double> stiff;      // c_ij beta_ij V_j  (N/m^4 per unit stretch in 3D)
  std::vector<double> s0;         // critical stretch of the bond
  std::vector<double> w0;         // beta_ij V_j, the bond's share of the initial neighbourhood
  std::vector<uint8_t> intact;    // 1 while the bond carries force
  std::size_t size() const { return partner.size(); }
};

// Crack-tip tracker (seed 003): the point with damage > threshold farthest along `direction`.
template <int Dim>
struct TipTracker {
  std::string name;
  Vec<Dim> direction = Vec<Dim>::UnitX();  // unit vector
  bool has_region = false;
  Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Zero();
};

// A traction t on a face, applied as the body force t / dx on the layer of points along that face
// (docs/peridynamics.md), with the MPM scenes' optional linear ramp to full value at rise_time.
template <int Dim>
struct PdLoad {
  std::string name;
  Vec<Dim> force_density = Vec<Dim>::Zero();  // N/m^3
  double rise_time = 0.0;
  std::vector<int32_t> points;
  double factor(double t) const { return rise_time > 0.0 && t < rise_time ? t / rise_time : 1.0; }
};

template <int Dim>
struct PdSystem : RunSettings {  // end time, dt, output, checks, damping (core/run_settings.hpp)
  Analysis analysis = Dim == 3 ? Analysis::ThreeD : Analysis::PlaneStress;
  double dx = 0.0, delta = 0.0, thickness = 1.0;
  int horizon_factor = 3;
  std::vector<PdMaterial> materials;
  std::vector<std::string> bodies;
  PdPoints<Dim> points;
  PdNeighbours<Dim> nb;
  std::size_t bond_count = 0;          // bonds (each counted once) after pre-cracks
  std::size_t precrack_bonds = 0;      // bonds removed by the scene's pre-cracks
  std::vector<PdLoad<Dim>> loads;      // tractions as body force on the boundary layer
  Vec<Dim> gravity = Vec<Dim>::Zero();
  double tip_threshold = 0.3;
  std::vector<TipTracker<Dim>> trackers;
};

}  // namespace cleave::pd
