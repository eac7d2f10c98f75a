// Meshing the scene's bodies with Gmsh (mesh.hpp). The shapes become OpenCASCADE entities
// (gmsh_shapes.cpp), all bodies are fragmented together so that touching bodies share the nodes of
// their common boundary, the fragments tell overlapping bodies apart, and the elements go through
// the checks every PEM mesh passes (mesh_build.cpp).
#include "libmpm/pem/mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>

#include "libmpm/core/error.hpp"
#include "libmpm/geometry/shape.hpp"
#include "libmpm/pem/gmsh_session.hpp"
#include "libmpm/pem/gmsh_shapes.hpp"
#include "libmpm/pem/mesh_build.hpp"

namespace cleave::pem {
namespace {

using detail::DimTags;
using detail::Fail;

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

// Nodes per size^Dim of body measure in Gmsh's unstructured meshes, boundary included (Gmsh 4.8.4):
// a disk at size r/40 has 1.20, at r/10 1.32, an 8 x 1 rectangle at 0.1 1.31; a sphere at r/20 0.82,
// at r/10 0.98, at r/5 1.25, a cube at 1/20 0.92. Fine meshes are the ones the limit is for.
template <int Dim>
constexpr double kNodesPerCell = Dim == 2 ? 1.2 : 1.0;

// The body a Gmsh meshing message names ("... surface 3 ..."), for the error's key.
int body_in_message(const std::string& message, int dim, const std::map<int, int>& piece_body) {
  static const std::regex entity(R"((surface|volume) (\d+))");
  for (auto it = std::sregex_iterator(message.begin(), message.end(), entity); it != std::sregex_iterator(); ++it) {
    if (((*it)[1] == "volume") != (dim == 3)) continue;
    const auto found = piece_body.find(std::stoi((*it)[2]));
    if (found != piece_body.end()) return found->second;
  }
  return -1;
}

// The curves of a plane surface with four straight sides, or nothing.
std::vector<int> four_sides(int surface) {
  DimTags curves;
  gmsh::model::getBoundary({{2, surface}}, curves, false, false, false);
  std::vector<int> out;
  for (const auto& c : curves) {
    std::string type;
    gmsh::model::getType(1, std::abs(c.second), type);
    if (type != "Line") return {};
    out.push_back(std::abs(c.second));
  }
  return out.size() == 4 ? out : std::vector<int>{};
}

// Transfinite constraints on a lone rectangle (surface) or box (volume) that fragmenting left with
// its four sides / six faces: N = round(edge / size) + 1 nodes per edge. A body split by a neighbour
// (a corner of another body on its edge) is meshed unstructured.
template <int Dim>
bool make_structured(int entity, double size, double unit) {
  std::vector<int> faces{entity};
  if constexpr (Dim == 3) {
    DimTags f;
    gmsh::model::getBoundary({{3, entity}}, f, false, false, false);
    if (f.size() != 6) return false;
    faces.clear();
    for (const auto& x : f) faces.push_back(std::abs(x.second));
  }
  std::set<int> curves;
  for (int s : faces) {
    const std::vector<int> c = four_sides(s);
    if (c.empty()) return false;
    curves.insert(c.begin(), c.end());
  }
  if (curves.size() != (Dim == 2 ? 4u : 12u)) return false;
  for (int c : curves) {
    double length = 0.0;
    gmsh::model::occ::getMass(1, c, length);
    const long n = std::max(1L, std::lround(length * unit / size)) + 1;
    gmsh::model::mesh::setTransfiniteCurve(c, static_cast<int>(n));
  }
  for (int s : faces) gmsh::model::mesh::setTransfiniteSurface(s);
  if constexpr (Dim == 3) gmsh::model::mesh::setTransfiniteVolume(entity);
  return true;
}

// 3D quads: hexahedra where a structured box's faces may be recombined, that is where every face it
// shares is shared with another such box (a tetrahedral neighbour cannot meet a quadrangle face).
void recombine_boxes(std::set<int> boxes) {
  for (bool changed = true; changed;) {
    changed = false;
    for (auto it = boxes.begin(); it != boxes.end();) {
      DimTags faces;
      gmsh::model::getBoundary({{3, *it}}, faces, false, false, false);
      bool alone = true;
      for (const auto& f : faces) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(2, std::abs(f.second), up, down);
        for (int v : up) alone = alone && (v == *it || boxes.count(v));
      }
      if (alone) {
        ++it;
      } else {
        it = boxes.erase(it);
        changed = true;
      }
    }
  }
  for (int b : boxes) {
    DimTags faces;
    gmsh::model::getBoundary({{3, b}}, faces, false, false, false);
    for (const auto& f : faces) gmsh::model::mesh::setRecombine(2, std::abs(f.second));
  }
}

}  // namespace

template <int Dim>
Mesh<Dim> mesh_bodies(const std::vector<BodyShape>& bodies, double length_scale, const MeshOptions& opt,
                      const std::string& size_key, std::size_t max_nodes) {
  if (bodies.empty()) throw std::invalid_argument("mesh_bodies: no body to mesh");
  if (!(std::isfinite(opt.size) && opt.size > 0.0))
    throw SceneError(size_key, "the element size must be > 0, got " + number(opt.size) + " m");
  // The scene reader's checks first, so a bad shape gets its usual message; its bounds frame the model.
  geom::Box<Dim> box;
  for (const BodyShape& b : bodies) {
    if (!b.shape) throw std::invalid_argument("mesh_bodies: body '" + b.name + "' has no shape");
    box = box.united(geom::parse_shape<Dim>(*b.shape, b.path, length_scale)->bounds());
  }
  const double extent = (box.hi - box.lo).maxCoeff();
  const detail::ModelFrame<Dim> frame{box.lo, extent > 0.0 ? extent : 1.0, length_scale};
  const std::string size_text = number(opt.size) + " m";

  detail::GmshSession session;
  auto fail_at = [](const std::string& key, const std::string& what) -> Fail {
    return [key, what](const std::string& why) { throw SceneError(key, what + why); };
  };

  // Each body's entities, then all of them fragmented together.
  DimTags inputs;
  std::vector<int> input_body;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    DimTags e;
    detail::gmsh_guarded([&] { e = detail::occ_shape<Dim>(*bodies[i].shape, bodies[i].path, frame); },
                         fail_at(bodies[i].path, "Gmsh cannot build this shape: "));
    inputs.insert(inputs.end(), e.begin(), e.end());
    input_body.insert(input_body.end(), e.size(), static_cast<int>(i));
  }
  const std::string all_key = bodies.size() == 1 ? bodies[0].path : "bodies";
  std::vector<DimTags> pieces_of(inputs.size());
  detail::gmsh_guarded(
      [&] {
        if (inputs.size() > 1) {
          DimTags out;
          gmsh::model::occ::fragment(inputs, {}, out, pieces_of);
        } else {
          pieces_of = {inputs};
        }
        gmsh::model::occ::synchronize();
      },
      fail_at(all_key, "Gmsh cannot join the bodies: "));
  // A piece that comes from two bodies is where they overlap.
  std::map<int, int> piece_body;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    for (const auto& [dim, tag] : pieces_of[k]) {
      if (dim != Dim) continue;
      const auto [it, added] = piece_body.emplace(tag, input_body[k]);
      if (added || it->second == input_body[k]) continue;
      const BodyShape& earlier = bodies[static_cast<std::size_t>(it->second)];
      const BodyShape& later = bodies[static_cast<std::size_t>(input_body[k])];
      throw SceneError(later.path, "body '" + later.name + "' overlaps body '" + earlier.name +
                                       "'; bodies may touch (they then share the nodes of their common boundary) "
                                       "but not overlap");
    }
  }

  std::vector<std::pair<int, int32_t>> entity_regions;  // body by body, pieces by tag
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (const auto& [tag, body] : piece_body)
      if (body == static_cast<int>(i)) entity_regions.emplace_back(tag, body);

  detail::gmsh_guarded(
      [&] {
        double measure = 0.0;
        for (const auto& [tag, body] : piece_body) {
          double m = 0.0;
          gmsh::model::occ::getMass(Dim, tag, m);
          measure += m * std::pow(frame.unit, Dim);
        }
        const double nodes = kNodesPerCell<Dim> * measure / std::pow(opt.size, Dim);
        if (nodes > static_cast<double>(max_nodes))
          throw SceneError(size_key, "meshing the bodies (" + number(measure) + (Dim == 2 ? " m^2" : " m^3") +
                                         ") at element size " + size_text + " would give about " + number(nodes) +
                                         " nodes, more than the " + std::to_string(max_nodes) +
                                         " allowed; use a larger element size");

        std::set<int> boxes;
        for (const auto& [tag, body] : entity_regions) {
          const nlohmann::json& s = *bodies[static_cast<std::size_t>(body)].shape;
          const bool lone = std::count_if(entity_regions.begin(), entity_regions.end(),
                                          [&](const auto& e) { return e.second == body; }) == 1;
          if (opt.structured && lone && s["type"] == (Dim == 2 ? "rectangle" : "box") &&
              make_structured<Dim>(tag, opt.size, frame.unit))
            boxes.insert(tag);
        }
        gmsh::option::setNumber("Mesh.ElementOrder", 1);
        gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
        gmsh::option::setNumber("Mesh.MeshSizeMax", opt.size / frame.unit);
        // Triangles recombined into quadrangles (Blossom), which may leave a few triangles. Not with
        // Gmsh's frontal-Delaunay for quadrangles (Mesh.Algorithm 8): Gmsh 4.8.4 crashes in it
        // (a segmentation fault in its background mesh, even on a lone disk).
        if (Dim == 2 && opt.quads) gmsh::option::setNumber("Mesh.RecombineAll", 1);
        if (Dim == 3 && opt.quads) recombine_boxes(boxes);
      },
      fail_at(size_key, "Gmsh cannot set the mesh up: "));

  std::string message;
  try {
    gmsh::model::mesh::generate(Dim);
  } catch (...) {
    message = detail::gmsh_failure();
  }
  if (!message.empty()) {
    const int b = body_in_message(message, Dim, piece_body);
    throw SceneError(b >= 0 ? bodies[static_cast<std::size_t>(b)].path : all_key,
                     "Gmsh cannot mesh " + std::string(b >= 0 ? "this shape" : "the bodies") + " at element size " +
                         size_text + ": " + message);
  }

  detail::RawMesh raw;
  detail::gmsh_guarded([&] { raw = detail::gmsh_elements(Dim, entity_regions, fail_at(size_key, "the mesh Gmsh made: ")); },
                       fail_at(size_key, "Gmsh cannot give its mesh: "));
  std::vector<std::size_t> count(bodies.size(), 0);
  for (int32_t r : raw.region) ++count[static_cast<std::size_t>(r)];
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (count[i] == 0)
      throw SceneError(bodies[i].path,
                       "Gmsh made no element of this shape at element size " + size_text + detail::gmsh_complaints());
  for (const BodyShape& b : bodies) raw.regions.push_back(b.name);
  const auto to_metres = [&frame](const Vec<3>& x) -> Vec<Dim> { return frame.origin + frame.unit * x.head<Dim>(); };
  return detail::finish_mesh<Dim>(std::move(raw), to_metres, fail_at(size_key, "the mesh Gmsh made: "));
}

template Mesh<2> mesh_bodies<2>(const std::vector<BodyShape>&, double, const MeshOptions&, const std::string&, std::size_t);
template Mesh<3> mesh_bodies<3>(const std::vector<BodyShape>&, double, const MeshOptions&, const std::string&, std::size_t);

}  // namespace cleave::pem
