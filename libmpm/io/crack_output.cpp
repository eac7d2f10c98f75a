#include "libmpm/io/crack_output.hpp"

#include <stdexcept>

namespace cleave::io {

Vec<2> crack_opening(const crack::Crack2D& c, std::size_t i) {
  Vec<2> t = Vec<2>::Zero();
  if (i > 0) t += (c.points[i] - c.points[i - 1]).normalized();
  if (i + 1 < c.points.size()) t += (c.points[i + 1] - c.points[i]).normalized();
  t.normalize();
  const Vec<2> n(-t.y(), t.x());  // left of the crack direction: towards the surface above
  const Vec<2> cod = c.above[i] - c.below[i];
  return {cod.dot(n), cod.dot(t)};
}

PointSet crack_point_set(const std::vector<crack::Crack2D>& cracks) {
  PointSet ps;
  PointArray above{"above", 3, {}}, below{"below", 3, {}}, cod{"cod", 3, {}};
  PointArray cn{"cod_normal", 1, {}}, ct{"cod_tangential", 1, {}}, id{"crack", 1, {}};
  for (const auto& c : cracks) {
    std::vector<int64_t> line;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      line.push_back(static_cast<int64_t>(ps.size()));
      ps.points.insert(ps.points.end(), {c.points[i].x(), c.points[i].y(), 0.0});
      above.values.insert(above.values.end(), {c.above[i].x(), c.above[i].y(), 0.0});
      below.values.insert(below.values.end(), {c.below[i].x(), c.below[i].y(), 0.0});
      const Vec<2> d = c.above[i] - c.below[i];
      cod.values.insert(cod.values.end(), {d.x(), d.y(), 0.0});
      const Vec<2> o = crack_opening(c, i);
      cn.values.push_back(o[0]);
      ct.values.push_back(o[1]);
      id.values.push_back(c.id);
    }
    ps.polylines.push_back(std::move(line));
  }
  ps.arrays = {std::move(above), std::move(below), std::move(cod), std::move(cn), std::move(ct), std::move(id)};
  return ps;
}

PointSet crack_point_set(const std::vector<crack::Crack2D>& cracks, const std::vector<crack::TipRecord>& tips) {
  PointSet ps = crack_point_set(cracks);
  std::vector<std::size_t> first(cracks.size() + 1, 0);  // point index of each crack's first point
  for (std::size_t i = 0; i < cracks.size(); ++i) first[i + 1] = first[i] + cracks[i].points.size();
  PointArray j1{"J1", 1, {}}, j2{"J2", 1, {}}, k1{"KI", 1, {}}, k2{"KII", 1, {}};
  for (PointArray* a : {&j1, &j2, &k1, &k2}) a->values.assign(ps.size(), 0.0);
  for (const auto& t : tips) {
    const std::size_t i = t.end == 0 ? first[t.crack] : first[t.crack + 1] - 1;
    j1.values[i] = t.J1, j2.values[i] = t.J2, k1.values[i] = t.KI, k2.values[i] = t.KII;
  }
  for (PointArray* a : {&j1, &j2, &k1, &k2}) ps.arrays.push_back(std::move(*a));
  return ps;
}

PointSet crack_point_set(const std::vector<crack::ExplicitCrack<3>>& cracks) {
  PointSet ps;
  PointArray above{"above", 3, {}}, below{"below", 3, {}}, cod{"cod", 3, {}}, cn{"cod_normal", 1, {}};
  PointArray ct{"cod_tangential", 3, {}}, id{"crack", 1, {}};
  PointArray fn{"front_normal", 3, {}}, ft{"front_tangent", 3, {}}, fa{"front_ahead", 3, {}};
  auto put = [](PointArray& a, const Vec<3>& v) { a.values.insert(a.values.end(), {v.x(), v.y(), v.z()}); };
  for (const auto& c : cracks) {
    const auto first = static_cast<int64_t>(ps.size());
    const std::vector<Vec<3>> normal = crack::point_normals(c);
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      ps.points.insert(ps.points.end(), {c.points[i].x(), c.points[i].y(), c.points[i].z()});
      const Vec<3> d = c.above[i] - c.below[i];
      put(above, c.above[i]), put(below, c.below[i]), put(cod, d);
      cn.values.push_back(d.dot(normal[i]));
      put(ct, d - d.dot(normal[i]) * normal[i]);
      id.values.push_back(c.id);
    }
    for (const auto& t : c.simplices) ps.triangles.push_back({first + t[0], first + t[1], first + t[2]});
    for (PointArray* a : {&fn, &ft, &fa}) a->values.resize(3 * ps.size(), 0.0);
    for (const auto& f : c.fronts) {
      std::vector<int64_t> line;
      for (std::size_t k = 0; k < f.nodes.size(); ++k) {
        const int64_t p = first + f.nodes[k];
        line.push_back(p);
        for (int d = 0; d < 3; ++d)
          fn.values[3 * p + d] = f.normal[k][d], ft.values[3 * p + d] = f.tangent[k][d], fa.values[3 * p + d] = f.ahead[k][d];
      }
      if (f.closed && !line.empty()) line.push_back(line.front());
      ps.polylines.push_back(std::move(line));
    }
  }
  ps.arrays = {std::move(above), std::move(below), std::move(cod), std::move(cn), std::move(ct),
               std::move(id),    std::move(fn),    std::move(ft),  std::move(fa)};
  return ps;
}

PointSet crack_point_set(const std::vector<crack::ExplicitCrack<3>>& cracks, const std::vector<crack::FrontRecord>& fronts) {
  PointSet ps = crack_point_set(cracks);
  std::vector<std::size_t> first(cracks.size(), 0);  // each crack's first point in ps
  for (std::size_t c = 1; c < cracks.size(); ++c) first[c] = first[c - 1] + cracks[c - 1].points.size();
  PointArray j1{"J1", 1, {}}, j2{"J2", 1, {}}, k1{"KI", 1, {}}, k2{"KII", 1, {}}, k3{"KIII", 1, {}}, fl{"flag", 1, {}};
  for (PointArray* a : {&j1, &j2, &k1, &k2, &k3, &fl}) a->values.assign(ps.size(), 0.0);
  for (const auto& r : fronts) {
    const auto& c = cracks[static_cast<std::size_t>(r.crack)];
    const std::size_t i = first[r.crack] + static_cast<std::size_t>(c.fronts[r.front].nodes[r.node]);
    j1.values[i] = r.J1, j2.values[i] = r.J2, k1.values[i] = r.KI, k2.values[i] = r.KII, k3.values[i] = r.KIII;
    fl.values[i] = r.flag;
  }
  for (PointArray* a : {&j1, &j2, &k1, &k2, &k3, &fl}) ps.arrays.push_back(std::move(*a));
  return ps;
}

}  // namespace cleave::io
