// Small helpers every method uses to describe itself (`cleave check`) and its points in messages.
#pragma once
#include <cstddef>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "libmpm/core/run_settings.hpp"
#include "libmpm/core/types.hpp"

namespace cleave {

// printf into a string (the check lines are fixed-format figures).
inline std::string format(const char* f, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

inline const char* analysis_name(Analysis a) {
  return a == Analysis::PlaneStress ? "plane stress" : a == Analysis::PlaneStrain ? "plane strain" : "solid";
}

// The check line of a static scene (dynamic relaxation, method/relaxation.hpp); none otherwise.
inline void describe_static(const RunSettings& m, std::vector<std::string>& out) {
  if (m.static_tolerance > 0)
    out.push_back(format("static: dynamic relaxation (damping near critical for the lowest mode, from the Rayleigh "
                         "quotient), ends when the strain energy settles to %.3g; time.end %.6g s is the latest, the "
                         "steps above the most", m.static_tolerance, m.end_time));
}

// "(x, y) m"
template <int Dim>
std::string position_text(const Vec<Dim>& x) {
  std::ostringstream s;
  s << "(";
  for (int d = 0; d < Dim; ++d) s << (d ? ", " : "") << x[d];
  s << ") m";
  return s.str();
}

// Index of the largest velocity (the first of equals).
template <int Dim>
std::size_t fastest(const std::vector<Vec<Dim>>& v) {
  std::size_t f = 0;
  for (std::size_t p = 1; p < v.size(); ++p)
    if (v[p].squaredNorm() > v[f].squaredNorm()) f = p;
  return f;
}

}  // namespace cleave
