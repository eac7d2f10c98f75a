#include "libmpm/crack/tip_parameters.hpp"

#include <algorithm>
#include <cmath>

namespace cleave::crack {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec<2> local(const TipFrame& f, const Vec<2>& x) {
  const Vec<2> d = x - f.tip;
  return {d.dot(f.e1), d.dot(f.e2)};
}
Vec<2> global(const TipFrame& f, const Vec<2>& l) { return f.tip + l.x() * f.e1 + l.y() * f.e2; }

// Angle (in the tip frame) where the circle of radius r about the tip first meets the crack,
// walking in from the tip; pi when the crack ends inside the circle. Returned in (-2 pi, 0].
double crack_angle(const Crack2D& c, int end, const TipFrame& f, double r) {
  Vec<2> hit = f.tip - r * f.e1;  // a straight crack's answer
  for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
    const Vec<2> a = vertex_from_tip(c, end, k), b = vertex_from_tip(c, end, k + 1);
    if ((b - f.tip).norm() < r) continue;
    // |a + t (b - a) - tip| = r with a inside (or on) the circle: the larger root.
    const Vec<2> d = b - a, m = a - f.tip;
    const double A = d.squaredNorm(), B = 2.0 * m.dot(d), C = m.squaredNorm() - r * r;
    const double t = (-B + std::sqrt(std::max(0.0, B * B - 4.0 * A * C))) / (2.0 * A);
    hit = a + std::clamp(t, 0.0, 1.0) * d;
    break;
  }
  const Vec<2> l = local(f, hit);
  double th = std::atan2(l.y(), l.x());
  if (th > 0.0) th -= 2.0 * kPi;
  return th;
}

}  // namespace

Vec<2> vertex_from_tip(const Crack2D& c, int end, std::size_t k) {
  return end == 0 ? c.points[k] : c.points[c.points.size() - 1 - k];
}

TipFrame tip_frame(const Crack2D& c, int end) {
  TipFrame f;
  f.tip = vertex_from_tip(c, end, 0);
  f.e1 = (f.tip - vertex_from_tip(c, end, 1)).normalized();
  f.e2 = Vec<2>(-f.e1.y(), f.e1.x());
  return f;
}

CrackPoint point_behind_tip(const Crack2D& c, int end, double distance) {
  double left = distance;
  for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
    const Vec<2> a = vertex_from_tip(c, end, k), b = vertex_from_tip(c, end, k + 1);
    const double len = (b - a).norm();
    const Vec<2> ahead = (a - b) / len;  // the local e1: towards the tip
    if (left <= len || k + 2 == c.points.size()) {
      const double t = std::min(left, len);
      return {a - t * ahead, Vec<2>(-ahead.y(), ahead.x())};
    }
    left -= len;
  }
  return {c.points[0], Vec<2>::Zero()};  // unreachable: a crack has at least one segment
}

std::vector<ContourPoint> contour_points(const Crack2D& c, int end, const TipSettings& s, double cell) {
  const TipFrame f = tip_frame(c, end);
  const double r = s.radius * cell;
  const double th0 = crack_angle(c, end, f, r);
  const int n = s.points;
  std::vector<ContourPoint> out;
  out.reserve(n);
  if (s.contour == TipSettings::Contour::Circle) {
    const double dth = 2.0 * kPi / n;
    for (int i = 0; i < n; ++i) {
      const double th = th0 + (i + 0.5) * dth;
      const Vec<2> radial = std::cos(th) * f.e1 + std::sin(th) * f.e2;
      out.push_back({f.tip + r * radial, radial, r * dth});
    }
    return out;
  }
  // Square of half-side r, perimeter parameter s in [0, 8r) counter-clockwise from (r, -r).
  auto at = [&](double p, Vec<2>& x, Vec<2>& nrm) {
    p = std::fmod(p, 8.0 * r);
    if (p < 0.0) p += 8.0 * r;
    if (p < 2.0 * r) x = {r, -r + p}, nrm = {1, 0};
    else if (p < 4.0 * r) x = {r - (p - 2.0 * r), r}, nrm = {0, 1};
    else if (p < 6.0 * r) x = {-r, r - (p - 4.0 * r)}, nrm = {-1, 0};
    else x = {-r + (p - 6.0 * r), -r}, nrm = {0, -1};
  };
  const Vec<2> ray(std::cos(th0), std::sin(th0));
  const Vec<2> hit = r * ray / std::max(std::fabs(ray.x()), std::fabs(ray.y()));
  double p0;
  if (std::fabs(ray.x()) >= std::fabs(ray.y()))
    p0 = ray.x() > 0 ? hit.y() + r : 4.0 * r + (r - hit.y());
  else
    p0 = ray.y() > 0 ? 2.0 * r + (r - hit.x()) : 6.0 * r + (hit.x() + r);
  const double ds = 8.0 * r / n;
  for (int i = 0; i < n; ++i) {
    Vec<2> l, nl;
    at(p0 + (i + 0.5) * ds, l, nl);
    out.push_back({global(f, l), nl.x() * f.e1 + nl.y() * f.e2, ds});
  }
  return out;
}

bool inside_contour(const TipFrame& f, const TipSettings& s, double cell, const Vec<2>& x) {
  const Vec<2> l = local(f, x);
  const double r = s.radius * cell;
  return s.contour == TipSettings::Contour::Circle ? l.norm() < r : l.cwiseAbs().maxCoeff() < r;
}

double kolosov_kappa(Analysis a, double nu) {
  return a == Analysis::PlaneStress ? (3.0 - nu) / (1.0 + nu) : 3.0 - 4.0 * nu;
}

StressIntensity stress_intensity(double J1, double cod_I, double cod_II, double shear_modulus, double kappa) {
  StressIntensity k;
  const double A = 0.25 * (kappa + 1.0);  // A_I = A_II for a stationary crack
  const double g = std::max(J1, 0.0) * 2.0 * shear_modulus / A;  // A_I K_I^2 + A_II K_II^2, over A
  if (std::fabs(cod_I) >= std::fabs(cod_II)) {
    const double ratio = cod_I != 0.0 ? cod_II / cod_I : 0.0;  // gamma_21
    k.KI = (cod_I < 0.0 ? -1.0 : 1.0) * std::sqrt(g / (1.0 + ratio * ratio));
    k.KII = ratio * k.KI;
  } else {
    const double ratio = cod_I / cod_II;  // gamma_12
    k.KII = (cod_II < 0.0 ? -1.0 : 1.0) * std::sqrt(g / (1.0 + ratio * ratio));
    k.KI = ratio * k.KII;
  }
  return k;
}

}  // namespace cleave::crack
