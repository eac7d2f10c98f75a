// Two elastic spheres colliding head-on with frictionless contact between them (issue 18, validation
// 5): the contact duration against Hertz's, shared by tests/test_body_contact.cpp (1 mm cells) and
// tests/test_body_contact_long.cpp (0.5 mm).
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <utility>
#include <vector>

#include "support.hpp"

namespace cleave::test {

using nlohmann::json;

// Two soft spheres (R = 10 mm, E = 10 MPa, nu = 0.3, rho = 1 g/cm3) meet head-on at 2 m/s each, a
// quarter of them between the symmetry planes y = 0 and z = 0, 1 mm cells (10 across a radius).
// Hertz: t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5) with m* = m/2, R* = R/2, 1/E* = 2 (1 - nu^2) / E and v
// the closing speed: 1.073 ms; the largest approach 1.46 mm (0.15 R), the contact radius 2.7 mm.
// The duration is read from sphere a's mass-centre velocity: contact begins when it first drops by
// 0.1 % and ends when it last differs from its final value by as much; Hertz's impact is read the same
// way (hertz_read_duration: 0.943 t_c), and the ratio of the two is returned.
// Hertz's impact (m* d'' = -k d^(3/2), k = 4/3 E* sqrt(R*), d(0) = 0, d'(0) = vrel) read as the
// simulation is: from the first time the closing speed has changed by thr vrel to the last time it
// differs from its final value by as much (0.943 t_c at thr = 1e-3: the force ~ d^(3/2) is slow to
// rise and to fall). Symplectic Euler at t_c / 1e5.
inline double hertz_read_duration(double mstar, double k, double vrel, double thr) {
  const double tscale = std::pow(mstar * mstar / (k * k * vrel), 0.2), dt = 1e-5 * 3 * tscale;
  double d = 0, v = vrel, t = 0, first = -1, last = 0;
  std::vector<std::pair<double, double>> hist;
  while (d >= 0.0) {
    v -= dt * k * std::pow(std::max(d, 0.0), 1.5) / mstar;
    d += dt * v;
    t += dt;
    hist.emplace_back(t, v);
  }
  for (const auto& [ti, vi] : hist) {
    if (first < 0 && vrel - vi > thr * vrel) first = ti;
    if (std::fabs(vi - hist.back().second) > thr * vrel) last = ti;
  }
  return last - first;
}

inline double hertz_duration_ratio(double cell, double speed = 2.0) {
  auto quarter_sphere = [](double x) {
    return json{{"type", "difference"},
                {"shapes", {{{"type", "sphere"}, {"center", {x, 0, 0}}, {"radius", 10}},
                            {{"type", "box"}, {"min", {x - 11, -11, -11}}, {"max", {x + 11, 0, 11}}},
                            {{"type", "box"}, {"min", {x - 11, -11, -11}}, {"max", {x + 11, 11, 0}}}}}};
  };
  const json scene = {
      {"units", {{"length", "mm"}, {"stress", "MPa"}, {"density", "g/cm3"}, {"velocity", "m/s"}, {"time", "ms"}}},
      {"analysis", {{"type", "3d"}}},
      {"resolution", cell},
      {"grid", {{"min", {-12, -2, -2}}, {"max", {33, 12, 12}}}},
      {"mpm", {{"shape_function", "ugimp"}, {"stress_update", "USAVG"}}},
      {"materials", {test::material("soft", 10, 0.3, 1.0)}},
      {"bodies", {{{"name", "a"}, {"material", "soft"}, {"shape", quarter_sphere(0)}, {"velocity", {speed, 0, 0}}},
                  {{"name", "b"}, {"material", "soft"}, {"shape", quarter_sphere(21)}, {"velocity", {-speed, 0, 0}}}}},
      {"contact", {{{"bodies", {"a", "b"}}, {"law", "frictionless"}}}},
      {"loads", {{{"type", "symmetry"}, {"axis", "y"}, {"position", 0}}, {{"type", "symmetry"}, {"axis", "z"}, {"position", 0}}}},
      {"time", {{"end", 0.5 / speed + 1.3 * 1.073 * std::pow(2.0 / speed, 0.2)}, {"cfl", 0.5}}}};
  Model<3> m = build_model<3>(scene);
  auto st = make_stepper<3>(m);
  const Body& A = m.bodies[0];
  auto vx = [&] {
    double mv = 0, mm = 0;
    for (std::size_t p = A.first; p < A.first + A.count; ++p) mv += m.particles.mass[p] * m.particles.v[p].x(), mm += m.particles.mass[p];
    return mv / mm;
  };
  std::vector<double> t, v;
  const long steps = std::lround(m.end_time / m.dt);
  for (long k = 1; k <= steps; ++k) {
    EXPECT_FALSE(st->step());
    t.push_back(k * m.dt), v.push_back(vx());
  }
  const double v0 = speed, tol = 1e-3 * v0;
  std::size_t first = 0, last = 0;
  while (first < v.size() && v[first] > v0 - tol) ++first;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (std::fabs(v[k] - v.back()) > tol) last = k;
  EXPECT_LT(first, v.size());
  EXPECT_LT(last + 10, v.size()) << "the spheres must have parted before the end";
  const double E = 10e6, nu = 0.3, rho = 1000, R = 0.01, vrel = 2 * speed;
  const double mass = rho * 4.0 / 3.0 * M_PI * R * R * R, Es = E / (2 * (1 - nu * nu));
  const double tc = 2.868 * std::pow((mass / 2) * (mass / 2) / ((R / 2) * Es * Es * vrel), 0.2);
  const double duration = t[last] - t[first] + m.dt;
  const double ref = hertz_read_duration(mass / 2, 4.0 / 3.0 * Es * std::sqrt(R / 2), vrel, 1e-3);
  std::printf("cell %g mm: contact %.4f ms; Hertz t_c %.4f ms, read by the same thresholds %.4f ms (ratio %.3f); "
              "rebound %.3f m/s\n", cell, duration * 1e3, tc * 1e3, ref * 1e3, duration / ref, -v.back());
  return duration / ref;
}

}  // namespace cleave::test
