#include "viz/fit/williams.hpp"

#include <cmath>
#include <numbers>

namespace cleave::viz {

std::array<double, 3> williams_term(int n, double A, double B, double r, double th) {
  const double l = 0.5 * n, s = (n % 2) ? -1.0 : 1.0, f = l * std::pow(r, l - 1.0);
  const double c1 = std::cos((l - 1) * th), c3 = std::cos((l - 3) * th);
  const double s1 = std::sin((l - 1) * th), s3 = std::sin((l - 3) * th);
  return {f * (A * ((2 + l + s) * c1 - (l - 1) * c3) - B * ((2 + l - s) * s1 - (l - 1) * s3)),
          f * (A * ((2 - l - s) * c1 + (l - 1) * c3) - B * ((2 - l + s) * s1 + (l - 1) * s3)),
          f * (A * ((l - 1) * s3 - (l + s) * s1) + B * ((l - 1) * c3 - (l - s) * c1))};
}

double TipField::KI() const { return a.empty() ? 0.0 : std::sqrt(2 * std::numbers::pi) * a[0]; }
double TipField::KII() const { return b.empty() ? 0.0 : -std::sqrt(2 * std::numbers::pi) * b[0]; }
double TipField::T() const { return a.size() < 2 ? 0.0 : 4 * a[1]; }

std::array<double, 3> TipField::tip_frame_stress(double x, double y) const {
  const double dx = x - x0, dy = y - y0, c = std::cos(alpha), s = std::sin(alpha);
  const double u = c * dx + s * dy, v = -s * dx + c * dy;
  const double r = std::hypot(u, v), th = std::atan2(v, u);
  std::array<double, 3> sum{0, 0, 0};
  const std::size_t N = std::max(a.size(), b.size());
  for (std::size_t k = 0; k < N; ++k) {
    const double A = k < a.size() ? a[k] : 0.0, B = (k < b.size() && k != 1) ? b[k] : 0.0;
    if (A == 0 && B == 0) continue;
    const auto t = williams_term(int(k) + 1, A, B, r, th);
    for (int i = 0; i < 3; ++i) sum[i] += t[i];
  }
  return sum;
}

double TipField::stress_difference(double x, double y) const {
  const auto s = tip_frame_stress(x, y);
  return std::hypot(s[0] - s[1], 2 * s[2]);
}

TipField tip_field_from_K(double x0, double y0, double alpha, double KI, double KII, double T) {
  const double root = std::sqrt(2 * std::numbers::pi);
  TipField f;
  f.x0 = x0, f.y0 = y0, f.alpha = alpha;
  f.a = {KI / root, T / 4};
  f.b = {-KII / root, 0.0};
  return f;
}

}  // namespace cleave::viz
