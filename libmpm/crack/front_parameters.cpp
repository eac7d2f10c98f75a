#include "libmpm/crack/front_parameters.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace cleave::crack {

FrontFrame front_frame(const ExplicitCrack<3>& c, std::size_t front, std::size_t k) {
  const CrackFront& f = c.fronts[front];
  FrontFrame fr;
  fr.x = c.points[f.nodes[k]];
  fr.e1 = f.ahead[k];
  fr.e2 = f.normal[k];
  fr.e3 = fr.e1.cross(fr.e2);
  return fr;
}

std::vector<double> front_arc_lengths(const ExplicitCrack<3>& c, std::size_t front) {
  const CrackFront& f = c.fronts[front];
  std::vector<double> s(f.nodes.size(), 0.0);
  for (std::size_t k = 1; k < f.nodes.size(); ++k)
    s[k] = s[k - 1] + (c.points[f.nodes[k]] - c.points[f.nodes[k - 1]]).norm();
  return s;
}

std::vector<FrontContourPoint> front_contour_points(const FrontFrame& f, const TipSettings& s, double cell,
                                                    double theta0) {
  // The 2D contour (one code for both dimensions) about a tip at the origin of the plane whose axes
  // are e1 and e2, of a straight crack running back from it along theta0; its points laid into 3D.
  Crack2D straight;
  straight.points = {Vec<2>(std::cos(theta0), std::sin(theta0)) * (4.0 * s.radius * cell), Vec<2>::Zero()};
  std::vector<FrontContourPoint> out;
  for (const ContourPoint& p : contour_points(straight, 1, s, cell))
    out.push_back({f.x + p.x.x() * f.e1 + p.x.y() * f.e2, p.n.x() * f.e1 + p.n.y() * f.e2, p.length});
  return out;
}

bool inside_front_contour(const FrontFrame& f, const TipSettings& s, double cell, const Vec<3>& x) {
  const Vec<3> d = x - f.x;
  const Vec<2> l(d.dot(f.e1), d.dot(f.e2));
  const double r = s.radius * cell;
  return s.contour == TipSettings::Contour::Circle ? l.norm() < r : l.cwiseAbs().maxCoeff() < r;
}

StressIntensity3 stress_intensity3(double J1, double cod_I, double cod_II, double cod_III, double shear_modulus,
                                   double nu) {
  const double A = 1.0 - nu;  // (kappa + 1) / 4 with kappa = 3 - 4 nu
  // k: proportional to (K_I, K_II, K_III) (the openings over their near-tip factors), scaled so
  // that G = (A (K_I^2 + K_II^2) + K_III^2) / (2 mu). Dividing by the largest component first is
  // eqs. 49-57's choice of divisor; the result is the same scaling.
  Vec<3> k(cod_I, cod_II, A * cod_III);
  const double big = k.cwiseAbs().maxCoeff();
  if (!(big > 0.0)) k = Vec<3>(1.0, 0.0, 0.0);
  else k /= big;
  const double weight = A * (k[0] * k[0] + k[1] * k[1]) + k[2] * k[2];
  const double c = std::sqrt(std::max(J1, 0.0) * 2.0 * shear_modulus / weight);
  return {c * k[0], c * k[1], c * k[2]};
}

namespace {
constexpr double kPi = 3.14159265358979323846;

// The complete elliptic integral of the second kind E(k), k^2 = m, by the arithmetic-geometric mean.
double elliptic_e(double m) {
  double a = 1.0, g = std::sqrt(1.0 - m), sum = 0.5 * m, pow2 = 0.5;
  for (int i = 0; i < 40 && std::fabs(a - g) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + g), c = 0.5 * (a - g);
    g = std::sqrt(a * g), a = an;
    pow2 *= 2.0;
    sum += pow2 * c * c;
  }
  return kPi / (2.0 * a) * (1.0 - sum);
}
}  // namespace

double EllipseReference::phi(const Vec<3>& x) const {
  const Vec<3> d = x - center, minor = normal.cross(major);
  return std::atan2(d.dot(minor) / b, d.dot(major) / a);
}

StressIntensity3 EllipseReference::at(const FrontFrame& f) const {
  const double ph = phi(f.x);
  const Vec<3> t = stress * load_axis.dot(normal) * load_axis;  // remote traction on the crack plane
  const double snn = t.dot(normal);
  StressIntensity3 k;
  if (a == b) {
    const double root = std::sqrt(kPi * a);
    k.KI = 2.0 / kPi * snn * root;
    k.KII = 4.0 / (kPi * (2.0 - nu)) * t.dot(f.e1) * root;
    k.KIII = 4.0 * (1.0 - nu) / (kPi * (2.0 - nu)) * t.dot(f.e3) * root;
    return k;
  }
  // Irwin: the semi-axes a >= b of the formula are the larger and the smaller.
  const double big = std::max(a, b), small = std::min(a, b);
  const double ct = std::cos(ph), st = std::sin(ph);
  // (sin^2 + (b/a)^2 cos^2) with the angle measured from the major axis of the formula.
  const double s2 = a >= b ? st * st + (small / big) * (small / big) * ct * ct
                           : ct * ct + (small / big) * (small / big) * st * st;
  k.KI = snn * std::sqrt(kPi * small) / elliptic_e(1.0 - (small / big) * (small / big)) * std::pow(s2, 0.25);
  return k;
}

}  // namespace cleave::crack
