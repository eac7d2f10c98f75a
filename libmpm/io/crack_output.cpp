#include "libmpm/io/crack_output.hpp"

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

}  // namespace cleave::io
