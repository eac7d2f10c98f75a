// A particle equilibrium method model built from a scene ("method": "pem"; seed 004, docs/pem.md):
// particles at the nodes of a finite-element mesh, pairs between the particles of every element,
// pair stiffness calibrated element by element to the continuum, loads on nodes, all SI.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "libmpm/core/run_settings.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/pem/mesh.hpp"
#include "libmpm/pem/pair_law.hpp"

namespace cleave::pem {

struct PemMaterial {
  std::string name, type;
  double E = 0, nu_given = -1, density = 0;
  double tensile_strength = 0, fracture_energy = 0;  // 0: not given
  double yield_stress = 0, hardening = 0, ultimate_strain = 0;  // plastic law
  PairLaw law;  // set once the mesh is known (the cutoff from the fracture energy needs it)
  // What the calibration gave on this mesh (calibration.hpp): the network's effective E and nu and
  // its departure from isotropy, for `cleave check`.
  double E_network = 0, nu_network = 0, anisotropy = 0;
};

// Particles as a structure of arrays.
template <int Dim>
struct PemParticles {
  std::vector<Vec<Dim>> x0, u, v, a;
  std::vector<double> volume, mass;
  std::vector<double> size;       // (volume / thickness)^(1/Dim): the particle's spacing, for the renderer
  std::vector<int32_t> region;    // the region (body) of its first element
  std::vector<int32_t> material;  // material of its first element
  std::vector<uint8_t> fixed;     // bit d: velocity component d prescribed
  std::vector<Vec<Dim>> v_fixed;
  void resize(std::size_t n) {
    x0.resize(n), u.resize(n), v.resize(n), a.resize(n), volume.resize(n), mass.resize(n), size.resize(n);
    region.resize(n), material.resize(n), fixed.resize(n), v_fixed.resize(n);
  }
};

// Pairs of each particle, both directions (every pair appears in the list of each end): particle p
// owns entries [offset[p], offset[p+1]), sorted by partner. Both copies compute the same doubles
// (negated vectors) and so break, yield and slide together; each particle sums only its own entries:
// no atomics, the same result for any thread count (as peridynamics' bonds, docs/peridynamics.md).
struct PemPairs {
  std::vector<int64_t> offset;
  std::vector<int32_t> partner;
  std::vector<double> l0;       // reference length (m)
  std::vector<double> xi;       // reference vector x0[partner] - x0[owner], Dim numbers per entry (m)
  std::vector<double> k;        // stiffness (N/m), the sum of its elements' calibrated shares
  std::vector<int32_t> law;     // index into the model's materials: the weakest of its elements
  std::vector<uint8_t> intact;  // 1 while the pair carries attraction
  std::vector<uint8_t> initial; // 1: intact at t = 0 (0: cut by a pre-crack), for damage
  std::vector<double> b, alpha; // plastic balance length and back force (empty: no plastic material)
  // Pairs cut by a pre-crack: index into `cut_normal` (Dim numbers each: the crack's unit normal
  // there, either sign), -1 for the others. Their faces touch along the crack, not along the pair:
  // they repel only when pressed together across the crack and slide freely along it (pem_solver.cpp).
  std::vector<int32_t> cut;
  std::vector<double> cut_normal;
  std::size_t size() const { return partner.size(); }
};

// A ramped set of nodal forces: f(t) = factor(t) * force.
template <int Dim>
struct PemLoad {
  std::string name;
  double rise_time = 0.0;
  std::vector<int32_t> nodes;
  std::vector<Vec<Dim>> force;  // N, per node
  double factor(double t) const { return rise_time > 0.0 && t < rise_time ? t / rise_time : 1.0; }
};

// "pem.equilibrium": the run ends once the largest speed and the relative residual force stay under
// their tolerances for `checks` checks in a row (one check every `interval` steps).
struct Equilibrium {
  bool enabled = false;
  double velocity = 0.0;   // m/s
  double residual = 0.0;   // |F_int + F_ext| / max(|F_ext|, |F_int|) over free components (2-norms)
  int checks = 10;
  int interval = 10;
};

// "pem.tip_growth" (2D, tip_growth.hpp): pre-cracks grow from their tips by the maximum hoop stress
// criterion on K_I, K_II read from their faces, instead of by pairs breaking on their own stretch.
struct TipGrowthSettings {
  bool enabled = false;
  double radius = 0.0;     // m: the faces' jumps are fitted between 1 mesh size and this behind a tip
  double length = 0.0;     // m: how far a tip advances per growth (default 1 mesh size)
  double max_speed = 0.0;  // m/s: a tip grows again only after length / max_speed (default: Rayleigh speed)
};

// A tip of a pre-crack inside the bodies, tracked while it grows (reference coordinates).
template <int Dim>
struct GrowingTip {
  std::string crack;
  Vec<Dim> start = Vec<Dim>::Zero(), x = Vec<Dim>::Zero(), dir = Vec<Dim>::Zero();  // dir: unit, outward
  double modulus = 0.0;    // E' (Pa) of the material at the tip: E (plane stress), E / (1 - nu^2)
  double toughness = 0.0;  // K_Ic (Pa sqrt(m)) = sqrt(E' G_c)
  std::string material;
  int32_t growths = 0;
  int32_t stop = 0;       // 0 growing; why it stopped: 1 an edge, 2 a crack
  int32_t last_cut = -1;  // the first crack-normal index of its last advance
  double run = 0.0;       // m: the straight length behind it since its direction last changed
  double first_time = -1.0, last_time = -1.0, kink = 0.0;  // kink: first growth vs the pre-crack (rad, ccw)
  double first_KI = 0.0, first_KII = 0.0;                   // Pa sqrt(m), when it first grew
};

template <int Dim>
struct PemSystem : RunSettings {
  Analysis analysis = Dim == 3 ? Analysis::ThreeD : Analysis::PlaneStress;
  double thickness = 1.0;
  double mesh_size = 0.0;
  std::string mesh_source;  // "gmsh" or the file's name
  Mesh<Dim> mesh;
  std::vector<int32_t> element_material;
  std::vector<PemMaterial> materials;
  std::vector<std::string> regions;
  PemParticles<Dim> points;
  PemPairs pairs;
  std::size_t pair_count = 0, precrack_pairs = 0;
  std::vector<PemLoad<Dim>> loads;
  Vec<Dim> gravity = Vec<Dim>::Zero();
  double friction = 0.3;
  Equilibrium equilibrium;
  double break_limit = 1e-3;  // a step that breaks more than this fraction of the pairs is redone in halves
  int max_halvings = 5;
  bool stop_on_separation = true;
  double fragment_fraction = 0.01;
  TipGrowthSettings tip_growth;
  std::vector<GrowingTip<Dim>> tips;  // with tip growth: the pre-cracks' tips inside the bodies
};

}  // namespace cleave::pem
