// Crack growth from tracked tips for PEM ("pem.tip_growth", 2D; docs/pem.md, "Growth from the tips").
// Seed 004's rule breaks a pair when its own stretch passes the cutoff. At the tip of a sliding
// pre-crack the largest stretches lie on the crack's flanks, so which pair goes first, and with it
// the initiation direction, is set by the element edges at the tip (validation.md: -3 to +85 degrees
// over five meshes against 67.7). With tip growth the pairs do not break on their own: each tip's
// K_I and K_II come from the opening and sliding of the crack's faces behind it (displacement
// correlation: a jump of 8 K / E' sqrt(r / 2 pi) at r behind a tip, fitted over the cut pairs within
// `radius`; the T-stress opens and slides nothing, so it does not enter as it does a hoop stress read
// at a finite distance), and where the maximum hoop stress criterion (Erdogan & Sih 1963) holds,
// K_eq(theta_c) >= K_Ic = sqrt(E' G_c), the tip advances a set length at theta_c and the pairs
// crossing the new segment are cut, to touch and slide across it as a pre-crack's do. A tip stops
// where it leaves the bodies or meets a crack.
#pragma once
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "libmpm/core/units.hpp"
#include "libmpm/method/state_io.hpp"
#include "libmpm/pem/pem_model.hpp"

namespace cleave::pem {

template <int Dim>
class TipGrower {
 public:
  explicit TipGrower(PemSystem<Dim>& m);

  // One growth check of every active tip at time t (after a step). Returns the pairs cut (each once).
  std::size_t check(double t);

  // K_I and K_II of tip k now (Pa sqrt(m)) from its faces' jumps, each split along its own segment,
  // and `along`: the mean direction of the path where they were read (towards the tip); false where
  // no cut pair lies within reach behind it.
  bool intensities(std::size_t k, double& KI, double& KII, Vec<Dim>& along) const;

  nlohmann::json info() const;  // run.json's "tips"
  void save(StateWriter& w) const;
  void load(StateReader& r);

 private:
  void refresh_near(std::size_t k);  // the particles within reach of tip k
  std::size_t cut_pairs(const Vec<Dim>& a, const Vec<Dim>& b);  // cuts the intact pairs crossing a-b
  bool meets_crack(const GrowingTip<Dim>& tip, const Vec<Dim>& b) const;  // tip-b crosses another crack

  PemSystem<Dim>& m_;
  std::vector<std::vector<int32_t>> near_;  // per tip
  std::vector<Vec<Dim>> near_at_;           // where near_ was gathered, per tip
};

// Reads "pem.tip_growth" (SceneError naming the key) and finds the tips of the scene's cracks that lie
// inside the bodies (an end whose short step outwards is inside). Called once the mesh, the pairs and
// the materials are built (their pairs then have no cutoff: set_pair_law with breakable = false).
template <int Dim>
void read_tip_growth(const nlohmann::json& section, const std::string& key, const UnitSystem& units,
                     const std::vector<std::vector<Vec<Dim>>>& crack_points, const std::vector<std::string>& crack_names,
                     PemSystem<Dim>& m);

}  // namespace cleave::pem
