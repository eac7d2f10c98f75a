// The checks every PEM mesh passes (mesh_build.hpp) and element measures (mesh.hpp).
#include "libmpm/pem/mesh_build.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <stdexcept>

#include <Eigen/Geometry>  // cross

namespace cleave::pem {
namespace {

using Simplex = std::array<int, 4>;  // a triangle uses the first three

// Sub-simplices whose signed measures sum to the element's. Quadrangles have a second split (along
// the other diagonal) to tell a non-convex quadrangle (one split agrees in sign) from a tangled one
// (neither does). Hexahedra: six tetrahedra around the diagonal 0-6 (Gmsh's and VTK's corner order).
constexpr Simplex kTriangle[] = {{0, 1, 2, 0}};
constexpr Simplex kQuadA[] = {{0, 1, 2, 0}, {0, 2, 3, 0}};
constexpr Simplex kQuadB[] = {{1, 2, 3, 0}, {1, 3, 0, 0}};
constexpr Simplex kTetrahedron[] = {{0, 1, 2, 3}};
constexpr Simplex kHexahedron[] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                   {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};

std::span<const Simplex> split(int dim, int nodes) {
  if (dim == 2 && nodes == 3) return kTriangle;
  if (dim == 2 && nodes == 4) return kQuadA;
  if (dim == 3 && nodes == 4) return kTetrahedron;
  if (dim == 3 && nodes == 8) return kHexahedron;
  throw std::logic_error("pem mesh: no " + std::to_string(dim) + "D element of " + std::to_string(nodes) + " nodes");
}

template <int Dim>
double simplex_measure(const std::vector<Vec<Dim>>& x, const int32_t* e, const Simplex& s) {
  if constexpr (Dim == 2) {
    const Vec<2> a = x[e[s[1]]] - x[e[s[0]]], b = x[e[s[2]]] - x[e[s[0]]];
    return 0.5 * (a.x() * b.y() - a.y() * b.x());
  } else {
    const Vec<3> a = x[e[s[1]]] - x[e[s[0]]], b = x[e[s[2]]] - x[e[s[0]]], c = x[e[s[3]]] - x[e[s[0]]];
    return a.dot(b.cross(c)) / 6.0;
  }
}

template <int Dim>
double measure_of(const std::vector<Vec<Dim>>& x, const int32_t* e, std::span<const Simplex> parts) {
  double m = 0.0;
  for (const Simplex& s : parts) m += simplex_measure<Dim>(x, e, s);
  return m;
}

// Some sub-simplex clearly positive and another clearly negative.
template <int Dim>
bool mixed_signs(const std::vector<Vec<Dim>>& x, const int32_t* e, std::span<const Simplex> parts, double tol) {
  bool pos = false, neg = false;
  for (const Simplex& s : parts) {
    const double v = simplex_measure<Dim>(x, e, s);
    pos = pos || v > tol;
    neg = neg || v < -tol;
  }
  return pos && neg;
}

// The same element in the other orientation (a reflection of its node order).
void reorient(int dim, int nodes, int32_t* e) {
  if (nodes == 3 || (dim == 3 && nodes == 4)) std::swap(e[1], e[2]);        // triangle, tetrahedron
  else if (nodes == 4) std::swap(e[1], e[3]);                                // quadrangle: 0 3 2 1
  else for (int k = 0; k < 4; ++k) std::swap(e[k], e[k + 4]);                // hexahedron: top for bottom
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string point_text(const Vec<3>& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return b;
}

}  // namespace

namespace detail {

const char* kind_name(int dim, int nodes) {
  if (dim == 2 && nodes == 3) return "triangle";
  if (dim == 2 && nodes == 4) return "quadrangle";
  if (dim == 3 && nodes == 4) return "tetrahedron";
  if (dim == 3 && nodes == 8) return "hexahedron";
  return "element";
}

template <int Dim>
Mesh<Dim> finish_mesh(RawMesh raw, const std::function<Vec<Dim>(const Vec<3>&)>& to_metres, const Fail& fail) {
  const std::size_t np = raw.points.size();
  std::vector<int32_t> index(np, -1);
  for (int32_t p : raw.nodes) {
    if (p < 0 || static_cast<std::size_t>(p) >= np) throw std::logic_error("pem mesh: element node out of range");
    index[static_cast<std::size_t>(p)] = 0;
  }

  // A 2D mesh drawn in 3D space (z constant, not necessarily 0) is accepted; a tilted or curved one
  // is not a 2D body.
  if constexpr (Dim == 2) {
    std::size_t first = np;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (std::size_t p = 0; p < np; ++p) {
      if (index[p] < 0) continue;
      if (first == np) first = p;
      for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], raw.points[p][i]), hi[i] = std::max(hi[i], raw.points[p][i]);
    }
    if (first < np) {
      const double z0 = raw.points[first].z();
      const double tol = 1e-9 * std::max({hi[0] - lo[0], hi[1] - lo[1], std::abs(z0)});
      for (std::size_t p = 0; p < np; ++p) {
        if (index[p] < 0 || std::abs(raw.points[p].z() - z0) <= tol) continue;
        raise(fail, "a 2D mesh lies in a plane z = constant: point " + point_text(raw.points[p]) + " is off the plane z = " +
                        number(z0) + " of point " + point_text(raw.points[first]));
      }
    }
  }

  Mesh<Dim> m;
  for (std::size_t p = 0; p < np; ++p) {
    if (index[p] < 0) continue;
    index[p] = static_cast<int32_t>(m.nodes.size());
    m.nodes.push_back(to_metres(raw.points[p]));
  }
  m.element_offset = std::move(raw.offset);
  m.element_nodes = std::move(raw.nodes);
  for (int32_t& p : m.element_nodes) p = index[static_cast<std::size_t>(p)];
  m.element_region = std::move(raw.region);
  m.regions = std::move(raw.regions);

  const char* what = Dim == 2 ? "area" : "volume";
  const char* unit = Dim == 2 ? " m^2" : " m^3";
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    const int k = m.nodes_of(e);
    int32_t* el = m.element_nodes.data() + m.element_offset[e];
    auto name = [&] {
      std::string s = "element " + std::to_string(e) + " (";
      if (!raw.source_label.empty()) s += raw.source_label + " " + std::to_string(raw.source[e]) + ", ";
      return s + "a " + kind_name(Dim, k) + ")";
    };
    // Zero relative to the element's size: what rounding leaves of a flat element is ~1e-16 h^Dim.
    double h = 0.0;
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b) h = std::max(h, (m.nodes[el[a]] - m.nodes[el[b]]).norm());
    const double tol = 1e-12 * std::pow(h, Dim);
    const auto parts = split(Dim, k);
    const double v = measure_of<Dim>(m.nodes, el, parts);
    bool tangled = mixed_signs<Dim>(m.nodes, el, parts, tol);
    if (Dim == 2 && k == 4) tangled = tangled && mixed_signs<Dim>(m.nodes, el, kQuadB, tol);  // not merely non-convex
    if (tangled)
      raise(fail, name() + " is inverted: its corners are out of order (parts of it have " + what + "s of both signs; " +
                      what + " " + number(v) + unit + ")");
    if (std::abs(v) <= tol) raise(fail, name() + " has zero " + what + " (" + number(v) + unit + ")");
    if (v < 0.0) reorient(Dim, k, el);
  }
  return m;
}

template Mesh<2> finish_mesh<2>(RawMesh, const std::function<Vec<2>(const Vec<3>&)>&, const Fail&);
template Mesh<3> finish_mesh<3>(RawMesh, const std::function<Vec<3>(const Vec<3>&)>&, const Fail&);

}  // namespace detail

template <int Dim>
double element_measure(const Mesh<Dim>& m, std::size_t e) {
  return measure_of<Dim>(m.nodes, m.element(e), split(Dim, m.nodes_of(e)));
}

template double element_measure<2>(const Mesh<2>&, std::size_t);
template double element_measure<3>(const Mesh<3>&, std::size_t);

}  // namespace cleave::pem
