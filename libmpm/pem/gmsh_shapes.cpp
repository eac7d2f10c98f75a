#include "libmpm/pem/gmsh_shapes.hpp"

#include <gmsh.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "libmpm/core/error.hpp"

namespace cleave::pem::detail {
namespace {

using nlohmann::json;
namespace occ = gmsh::model::occ;

template <int Dim>
class Builder {
 public:
  explicit Builder(const ModelFrame<Dim>& f) : f_(f) {}

  DimTags build(const json& j, const std::string& path) const {
    const std::string type = j.at("type").get<std::string>();
    if (type == "union" || type == "difference") return combine(j, path, type == "union");
    if constexpr (Dim == 2) {
      if (type == "rectangle") {
        const Vec<2> lo = point(j["min"]), hi = point(j["max"]);
        return {{2, occ::addRectangle(lo.x(), lo.y(), 0.0, hi.x() - lo.x(), hi.y() - lo.y())}};
      }
      if (type == "disk") {
        const Vec<2> c = point(j["center"]);
        const double r = length(j["radius"]);
        return {{2, occ::addDisk(c.x(), c.y(), 0.0, r, r)}};
      }
      if (type == "ellipse") return ellipse(j);
      if (type == "polygon") return {{2, polygon(j["points"], 0.0)}};
    } else {
      if (type == "box") {
        const Vec<3> lo = point(j["min"]), hi = point(j["max"]);
        const Vec<3> d = hi - lo;
        return {{3, occ::addBox(lo.x(), lo.y(), lo.z(), d.x(), d.y(), d.z())}};
      }
      if (type == "sphere") {
        const Vec<3> c = point(j["center"]);
        return {{3, occ::addSphere(c.x(), c.y(), c.z(), length(j["radius"]))}};
      }
      if (type == "cylinder") return cylinder(j);
      if (type == "ellipsoid") {
        // A sphere of the first semi-axis stretched along y and z (OpenCASCADE has no ellipsoid).
        const Vec<3> c = point(j["center"]);
        const double a = length(j["semi_axes"][0]), b = length(j["semi_axes"][1]), cc = length(j["semi_axes"][2]);
        const int s = occ::addSphere(c.x(), c.y(), c.z(), a);
        occ::dilate({{3, s}}, c.x(), c.y(), c.z(), 1.0, b / a, cc / a);
        return {{3, s}};
      }
      if (type == "prism") return prism(j);
    }
    throw SceneError(path + ".type", "shape type '" + type + "' cannot be meshed for pem (no Gmsh builder for it)");
  }

 private:
  const ModelFrame<Dim>& f_;

  Vec<Dim> point(const json& p) const {
    Vec<Dim> x;
    for (int i = 0; i < Dim; ++i) x[i] = f_.coordinate(p[static_cast<std::size_t>(i)].get<double>(), i);
    return x;
  }
  double length(const json& v) const { return f_.length(v.get<double>()); }

  // A plane polygon at height z: points, lines, a curve loop, a surface (either orientation).
  int polygon(const json& pts, double z) const {
    std::vector<int> p, l;
    for (const json& q : pts) p.push_back(occ::addPoint(f_.coordinate(q[0].get<double>(), 0), f_.coordinate(q[1].get<double>(), 1), z));
    for (std::size_t i = 0; i < p.size(); ++i) l.push_back(occ::addLine(p[i], p[(i + 1) % p.size()]));
    return occ::addPlaneSurface({occ::addCurveLoop(l)});
  }

  DimTags ellipse(const json& j) const {
    const Vec<2> c = point(j["center"]);
    const double a = length(j["semi_axes"][0]), b = length(j["semi_axes"][1]);
    // The scene's angle is in degrees (geometry/primitives.cpp). OpenCASCADE wants the major radius
    // first: an ellipse taller than wide is a wide one turned a further quarter turn.
    double angle = (j.contains("angle") ? j["angle"].get<double>() : 0.0) * std::numbers::pi / 180.0;
    if (a < b) angle += 0.5 * std::numbers::pi;
    const int s = occ::addDisk(c.x(), c.y(), 0.0, std::max(a, b), std::min(a, b));
    if (angle != 0.0) occ::rotate({{2, s}}, c.x(), c.y(), 0.0, 0.0, 0.0, 1.0, angle);
    return {{2, s}};
  }

  DimTags cylinder(const json& j) const {
    // The scene's center is the middle of the axis (geometry/primitives.cpp); Gmsh starts at an end.
    const Vec<Dim> c = point(j["center"]);
    Vec<3> axis(j["axis"][0].get<double>(), j["axis"][1].get<double>(), j["axis"][2].get<double>());
    axis = (axis / axis.cwiseAbs().maxCoeff()).normalized();
    const Vec<3> d = axis * length(j["length"]);
    const Vec<3> base = c - 0.5 * d;
    return {{3, occ::addCylinder(base.x(), base.y(), base.z(), d.x(), d.y(), d.z(), length(j["radius"]))}};
  }

  DimTags prism(const json& j) const {
    const double z0 = f_.coordinate(j["z"][0].get<double>(), 2), z1 = f_.coordinate(j["z"][1].get<double>(), 2);
    const int base = polygon(j["points"], z0);
    DimTags out, volumes;
    occ::extrude({{2, base}}, 0.0, 0.0, z1 - z0, out);
    for (const auto& e : out)
      if (e.first == 3) volumes.push_back(e);
    return volumes;
  }

  DimTags combine(const json& j, const std::string& path, bool fuse) const {
    const json& shapes = j["shapes"];
    std::vector<DimTags> parts;
    for (std::size_t i = 0; i < shapes.size(); ++i)
      parts.push_back(build(shapes[i], path + ".shapes[" + std::to_string(i) + "]"));
    DimTags object = parts[0], tools, out;
    for (std::size_t i = 1; i < parts.size(); ++i) tools.insert(tools.end(), parts[i].begin(), parts[i].end());
    if (tools.empty()) return object;
    std::vector<DimTags> map;
    if (fuse) occ::fuse(object, tools, out, map);
    else occ::cut(object, tools, out, map);
    DimTags kept;
    for (const auto& e : out)
      if (e.first == Dim) kept.push_back(e);
    if (kept.empty()) throw SceneError(path + ".shapes", "the difference leaves nothing: the cuts cover all of shapes[0]");
    return kept;
  }
};

}  // namespace

template <int Dim>
DimTags occ_shape(const json& shape, const std::string& path, const ModelFrame<Dim>& frame) {
  return Builder<Dim>(frame).build(shape, path);
}

template DimTags occ_shape<2>(const json&, const std::string&, const ModelFrame<2>&);
template DimTags occ_shape<3>(const json&, const std::string&, const ModelFrame<3>&);

}  // namespace cleave::pem::detail
