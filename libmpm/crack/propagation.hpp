// Crack propagation, the closed-form parts (free of solver state): when a crack tip grows (an
// initiation criterion) and which way (a direction rule), each a small style registered by its
// scene name where it is defined (propagation_criteria.cpp, direction_rules.cpp), and the scene key
// cracks[i].propagation that picks them. The solver side (libmpm/mpm/crack_growth.hpp) evaluates
// J and K at the tips, asks these, and adds the new segments.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libmpm/core/registry.hpp"

namespace cleave::crack {

// What a criterion sees at a tip, in the tip's frame (e1 ahead, e2 its left normal; K_II > 0 when
// the "+" face slides ahead of the "-" face): the energy release rate J1 and K_I, K_II from
// crack_tip_eval, and the material's toughness at the tip (both spellings: G_c = K_Ic^2 / E').
struct TipLoading {
  double J = 0.0, KI = 0.0, KII = 0.0;
  double Gc = 0.0, KIc = 0.0;  // after the resistance curve
  double e_prime = 0.0;        // E' (plane strain E / (1 - nu^2), plane stress E): G = K^2 / E'
};

// An initiation criterion: the ratio of the driving quantity to its critical value; the tip grows
// when it reaches 1 (e.g. J / G_c).
using InitiationCriterion = std::function<double(const TipLoading&)>;
// A direction rule: the kink angle from e1 towards e2, radians, in (-pi/2, pi/2).
using DirectionRule = std::function<double(const TipLoading&)>;
struct DirectionRuleTag {};
using InitiationCriteria = NameTable<InitiationCriterion>;
using DirectionRules = NameTable<DirectionRule, DirectionRuleTag>;

// Maximum hoop stress (Erdogan & Sih 1963): the angle where sigma_theta_theta is largest,
// theta_c = 2 arctan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)] (0 for K_II = 0; K_I <= 0 takes the
// pure-mode-II limit of the sign of K_II, -+70.5 degrees).
double hoop_stress_angle(double KI, double KII);
// sigma_theta_theta sqrt(2 pi r) at angle theta: cos(theta/2) [K_I cos^2(theta/2) - 3/2 K_II sin theta].
double hoop_stress_intensity(double KI, double KII, double theta);
// The stress intensities of a small kink at theta, to first order (Cotterell & Rice 1980: the
// near-tip sigma_theta_theta and sigma_r_theta on the ray): {k_I(theta), k_II(theta)}.
std::pair<double, double> kink_intensities(double KI, double KII, double theta);
// The kink angle that maximises G(theta) = (k_I^2 + k_II^2) / E' (k_I >= 0), searched over
// |theta| <= 80 degrees to 1e-6 rad; 0 for a pure mode I tip.
double max_energy_release_angle(double KI, double KII);

// The Rayleigh wave speed from the shear modulus, density and Poisson's ratio (the root of the
// Rayleigh equation; nu of the solid: plane strain and 3D; a plate in plane stress passes
// nu / (1 + nu)).
double rayleigh_speed(double shear_modulus, double density, double nu);

// The scene key cracks[i].propagation (docs/scenes.md, "Growing cracks"):
//   "criterion": an InitiationCriteria name (default "energy_release_rate": J >= G_c),
//   "direction": a DirectionRules name (default "max_hoop_stress"),
//   "growth_length": the advance per growth, in cells, in [0.1, 2] (default 0.5),
//   "max_speed_cR": cap on the tip speed as a multiple of the Rayleigh speed, in (0, 2] (default 1: a
//                   brittle crack cannot outrun the Rayleigh wave, Freund 1990, but the criterion alone
//                   lets a tip grow a step at every check while J stays above G_c, half a cell a step),
//   "check_interval": steps between growth checks (default 1),
//   "resistance_curve": [[da, factor], ...]: the toughness times factor(da) after a growth of da
//                       (scene length unit), linear between the points, flat beyond (default 1).
struct Propagation {
  std::string criterion = "energy_release_rate";
  std::string direction = "max_hoop_stress";
  double growth_length = 0.5;  // cells
  double max_speed_cR = 1.0;
  int check_interval = 1;
  std::vector<std::pair<double, double>> resistance;  // (da in m, factor), da ascending
  // The resistance factor after a growth of da metres.
  double resistance_factor(double da) const;
};

// Reads cracks[i].propagation at key_path; length_scale converts the scene's lengths to metres.
// SceneError naming the key for an unknown criterion or direction (listing the valid ones), a
// growth length outside [0.1, 2] cells, a speed cap outside (0, 2], a check interval below 1, or a
// resistance curve that is not [[da >= 0 ascending, factor > 0], ...].
Propagation parse_propagation(const nlohmann::json& j, const std::string& key_path, double length_scale);

}  // namespace cleave::crack

// Registers an initiation criterion / a direction rule under its scene name; rank orders the list.
#define CLEAVE_REGISTER_INITIATION_CRITERION(name, rank, fn)                                  \
  namespace {                                                                                  \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_initiation_) =                           \
      ::cleave::crack::InitiationCriteria::instance().add(name, fn, rank);                    \
  }
#define CLEAVE_REGISTER_DIRECTION_RULE(name, rank, fn)                                        \
  namespace {                                                                                  \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_direction_) =                            \
      ::cleave::crack::DirectionRules::instance().add(name, fn, rank);                        \
  }
