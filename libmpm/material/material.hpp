// Constitutive laws. A material is a small class registered by name (see linear_elastic.cpp);
// the scene names it with "type". Stresses are Cauchy, strains small-strain tensor components,
// both in the Sym<Dim> layout of core/types.hpp.
#pragma once
#include <cmath>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "libmpm/core/error.hpp"
#include "libmpm/core/registry.hpp"
#include "libmpm/core/types.hpp"
#include "libmpm/core/units.hpp"

namespace cleave {

template <int Dim>
class Material {
 public:
  virtual ~Material() = default;
  // Advance stress and strain by the velocity gradient L over dt (one of the paper's Subtask 3).
  virtual void update(Sym<Dim>& stress, Sym<Dim>& strain, const Mat<Dim>& L, double dt) const = 0;
  // The strain that goes with `stress`, for laws where one determines the other (a solver then need
  // not carry the strain through the steps): true and the strain into `strain`, else false.
  virtual bool strain_from_stress(const Sym<Dim>& stress, Sym<Dim>& strain) const {
    (void)stress, (void)strain;
    return false;
  }
  // Stored elastic energy per unit volume for the current state.
  virtual double strain_energy_density(const Sym<Dim>& stress, const Sym<Dim>& strain) const = 0;
  // Isotropic elastic constants, for K from J at crack tips: true and the shear modulus and
  // Poisson's ratio when the law has them.
  virtual bool isotropic_elastic(double& shear_modulus, double& poisson) const {
    (void)shear_modulus, (void)poisson;
    return false;
  }
  // Largest wave speed (for the stable time step).
  virtual double wave_speed() const = 0;
  double density() const { return density_; }
  const std::string& name() const { return name_; }
  // Fracture toughness, for growing cracks (crack::Propagation): the scene gives G_c (J/m^2) or
  // K_Ic (Pa sqrt(m)), the other being 0 here; both 0 when it gives neither.
  double toughness_Gc() const { return Gc_; }
  double toughness_KIc() const { return KIc_; }

 protected:
  double density_ = 0.0;
  std::string name_;
  double Gc_ = 0.0, KIc_ = 0.0;
  // Reads the optional toughness keys "G_c" (or "fracture_energy", peridynamics' spelling, so that
  // one material serves both methods) and "K_Ic", at most one of them, each > 0.
  template <class Reader>
  void read_toughness(const Reader& r, const UnitSystem& units) {
    const char* given[] = {"G_c", "fracture_energy", "K_Ic"};
    const char* first = nullptr;
    for (const char* k : given)
      if (r.has(k)) {
        if (first) throw SceneError(r.at(k), std::string("give one toughness, not both \"") + first + "\" and \"" + k + "\"");
        first = k;
      }
    const double stress = units.factor(Quantity::Stress), length = units.factor(Quantity::Length);
    if (r.has("K_Ic")) KIc_ = r.positive("K_Ic", stress * std::sqrt(length));
    else if (first) Gc_ = r.positive(first, stress * length);
  }
};

// 2 / (1 + q2), the scale of the Cayley rotation R = I + 2/(1 + |q|^2) (Q + Q^2). A step turns a particle
// by a small angle (|q| below 1e-4 in every scene we run: 5e-5 for the disk spun at 1 rad/ms on 1 mm
// cells), where the series 2 (1 - q2 + q2^2) equals it to 1e-24 relative (the next term, q2^3), far below
// round-off: the division it replaces lay on the stress update's critical path (docs/performance.md,
// "Issue 14's performance").
CLEAVE_INLINE inline double cayley_scale(double q2) {
  if (q2 < 1e-8) [[likely]]
    return 2.0 * (1.0 + q2 * (q2 - 1.0));
  return 2.0 / (1.0 + q2);
}

// The material's turn over dt, R the Cayley (Hughes-Winget) rotation of the spin W = (L - L^T)/2,
// which is exactly orthogonal (a spinning body keeps its stress's invariants to round-off) and
// second-order accurate in the angle; apply(t) turns a symmetric tensor (Sym layout): t <- R t R^T.
// Incremental (hypoelastic) laws turn their stress (and strain, if they carry one) before adding
// their increment, so that a body that turns carries its stress with it: without it a stressed body
// turned by an angle theta keeps its stress components in the fixed axes, an error of order theta
// times the stress (docs/validation.md, spinning bodies). Objective. The coefficients once per update.
template <int Dim>
struct SpinRotation {
  CLEAVE_INLINE explicit SpinRotation(const Mat<Dim>& L, double dt) {
    if constexpr (Dim == 2) {
      // In 2D a turn by phi leaves the mean (xx + yy)/2 and turns the pair ((xx - yy)/2, xy) by 2 phi.
      // cos 2 phi = c^2 - s^2 and sin 2 phi = 2 c s, with c = (1 - q^2) k / 2, s = q k, k = cayley_scale.
      const double q = 0.25 * (L(1, 0) - L(0, 1)) * dt;  // tan(phi / 2), phi the angle turned counter-clockwise
      const double q2 = q * q, k = cayley_scale(q2), c = 0.5 * (1.0 - q2) * k, s = q * k;
      C = c * c - s * s, S = 2.0 * c * s;
    } else {
      // q: half the rotation vector; R = I + 2/(1 + |q|^2) (Q + Q^2), Q v = q x v, and with
      // Q^2 = q q^T - |q|^2 I: R = (1 - k |q|^2) I + k Q + k q q^T, k = 2 / (1 + |q|^2). On scalars:
      // as Eigen expressions R and R T R^T were out-of-line calls, 4 % of a 3D step's time.
      const double qx = 0.25 * dt * (L(2, 1) - L(1, 2)), qy = 0.25 * dt * (L(0, 2) - L(2, 0)),
                   qz = 0.25 * dt * (L(1, 0) - L(0, 1));
      const double q2 = qx * qx + qy * qy + qz * qz, k = cayley_scale(q2), c = 1.0 - k * q2;
      const double r[3][3] = {{c + k * qx * qx, k * (qx * qy - qz), k * (qx * qz + qy)},
                              {k * (qy * qx + qz), c + k * qy * qy, k * (qy * qz - qx)},
                              {k * (qz * qx - qy), k * (qz * qy + qx), c + k * qz * qz}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[i][j] = r[i][j];
    }
  }
  CLEAVE_INLINE void apply(Sym<Dim>& x) const {
    if constexpr (Dim == 2) {
      const double mean = 0.5 * (x[0] + x[1]), dev = 0.5 * (x[0] - x[1]), xy = x[3];
      const double dev2 = C * dev - S * xy;
      x[0] = mean + dev2;
      x[1] = mean - dev2;
      x[3] = S * dev + C * xy;
    } else {
      const double T[3][3] = {{x[0], x[3], x[5]}, {x[3], x[1], x[4]}, {x[5], x[4], x[2]}};
      double A[3][3];  // R T
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A[i][j] = R[i][0] * T[0][j] + R[i][1] * T[1][j] + R[i][2] * T[2][j];
      // (R T R^T)_ij = sum_k A_ik R_jk, symmetric: the upper triangle, averaged with the lower. (Forced
      // inline: GCC left the lambda out of line, a call per component, 5 % of the rod's 3D step.)
      const auto U = [&](int i, int j) CLEAVE_INLINE { return A[i][0] * R[j][0] + A[i][1] * R[j][1] + A[i][2] * R[j][2]; };
      x[0] = U(0, 0), x[1] = U(1, 1), x[2] = U(2, 2);
      x[3] = 0.5 * (U(0, 1) + U(1, 0)), x[4] = 0.5 * (U(1, 2) + U(2, 1)), x[5] = 0.5 * (U(0, 2) + U(2, 0));
    }
  }
  double C = 1.0, S = 0.0;  // 2D: cos and sin of twice the angle
  double R[3][3] = {};      // 3D: the rotation
};

// Arguments to a material factory: its JSON object, its key path for errors, units and analysis.
struct MaterialArgs {
  const nlohmann::json& json;
  std::string key_path;
  const UnitSystem& units;
  Analysis analysis;
};

template <int Dim>
using MaterialRegistry = Registry<Material<Dim>, const MaterialArgs&>;

}  // namespace cleave

// Registers a material class template (taking the dimension, constructed from MaterialArgs) for 2D
// and 3D under `name`, the scene's "type". Put it in the material's own .cpp.
#define CLEAVE_REGISTER_MATERIAL(name, Class)                                                       \
  namespace {                                                                                       \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_material_2_) =                                \
      ::cleave::MaterialRegistry<2>::instance().add(name, [](const ::cleave::MaterialArgs& a) {     \
        return std::unique_ptr<::cleave::Material<2>>(new Class<2>(a));                             \
      });                                                                                           \
  [[maybe_unused]] const bool CLEAVE_REGISTRAR(cleave_material_3_) =                                \
      ::cleave::MaterialRegistry<3>::instance().add(name, [](const ::cleave::MaterialArgs& a) {     \
        return std::unique_ptr<::cleave::Material<3>>(new Class<3>(a));                             \
      });                                                                                           \
  }
