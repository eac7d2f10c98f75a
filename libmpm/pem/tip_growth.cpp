#include "libmpm/pem/tip_growth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libmpm/core/error.hpp"
#include "libmpm/core/json_reader.hpp"
#include "libmpm/crack/crack2d.hpp"
#include "libmpm/crack/crossing.hpp"
#include "libmpm/crack/propagation.hpp"
#include "libmpm/method/describe.hpp"

namespace cleave::pem {
namespace {

// The closed segments a-b and c-d meet (crack::segments_intersect), unless all four points are
// collinear: a pair lying along the new crack segment is not cut by it.
bool segments_meet(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c, const Vec<2>& d) {
  if (crack::area_sign(a, b, c) == 0 && crack::area_sign(a, b, d) == 0) return false;
  return crack::segments_intersect(a, b, c, d);
}

// A particle of `points` lies within r of x (reference positions).
template <int Dim>
bool particle_within(const std::vector<Vec<Dim>>& points, const Vec<Dim>& x, double r) {
  for (const auto& p : points)
    if ((p - x).squaredNorm() < r * r) return true;
  return false;
}

// Calls visit(e, i, j) for each pair (i < j, entry e of i) whose segment meets a-b (segments_meet),
// until it returns true; returns whether it did. Only particles within |b - a| + 4 mesh sizes of a
// are looked at: a crossing pair's ends lie that near.
template <class Visit>
bool for_pairs_crossing(const PemPairs& N, const std::vector<Vec<2>>& X, const Vec<2>& a, const Vec<2>& b,
                        double mesh_size, Visit visit) {
  const double reach = (b - a).norm() + 4.0 * mesh_size;
  for (std::size_t i = 0; i < X.size(); ++i) {
    if ((X[i] - a).squaredNorm() > reach * reach) continue;
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
      const auto j = static_cast<std::size_t>(N.partner[e]);
      if (j > i && segments_meet(X[i], X[j], a, b) && visit(e, i, j)) return true;
    }
  }
  return false;
}

template <int Dim>
std::vector<double> as_vector(const Vec<Dim>& x) {
  return std::vector<double>(x.data(), x.data() + Dim);
}

}  // namespace

template <int Dim>
TipGrower<Dim>::TipGrower(PemSystem<Dim>& m) : m_(m) {
  near_.resize(m_.tips.size());
  near_at_.assign(m_.tips.size(), Vec<Dim>::Constant(std::numeric_limits<double>::quiet_NaN()));
}

template <int Dim>
void TipGrower<Dim>::refresh_near(std::size_t k) {
  const auto& tip = m_.tips[k];
  if (near_at_[k] == tip.x) return;
  const double reach = m_.tip_growth.radius + 2.0 * m_.mesh_size;
  near_[k].clear();
  for (std::size_t p = 0; p < m_.points.x0.size(); ++p)
    if ((m_.points.x0[p] - tip.x).squaredNorm() <= reach * reach) near_[k].push_back(static_cast<int32_t>(p));
  near_at_[k] = tip.x;
}

template <int Dim>
bool TipGrower<Dim>::intensities(std::size_t k, double& KI, double& KII, Vec<Dim>& along) const {
  if constexpr (Dim != 2) {
    (void)k, (void)KI, (void)KII, (void)along;
    return false;
  } else {
    const auto& tip = m_.tips[k];
    const auto& N = m_.pairs;
    const auto& P = m_.points;
    const Vec<2> up(-tip.dir[1], tip.dir[0]);  // the tip's left normal: its "upper" face
    const double inner = m_.mesh_size, outer = m_.tip_growth.radius;
    // Least squares of jump = c sqrt(rho) over the cut pairs whose midpoints lie between inner and
    // outer from the tip and behind it; each jump split along its own crack segment's normal
    // (oriented to the upper side) and tangent (towards the tip).
    double sn = 0, st = 0, ss = 0;
    Vec<2> sum_t = Vec<2>::Zero();
    for (int32_t i : near_[k]) {
      for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e) {
        const int32_t j = N.partner[e];
        if (j < i || N.intact[e] || N.cut[e] < 0) continue;
        const Vec<2> mid = 0.5 * (P.x0[i] + P.x0[j]);
        const double rho = (mid - tip.x).norm();
        if (rho < inner || rho > outer || (mid - tip.x).dot(tip.dir) > 0.0) continue;
        Vec<2> n(N.cut_normal[2 * N.cut[e]], N.cut_normal[2 * N.cut[e] + 1]);
        if (n.dot(up) < 0) n = -n;
        const Vec<2> t(n[1], -n[0]);  // n rotated by -90 degrees: along the crack, towards the tip
        const bool i_up = (P.x0[i] - mid).dot(n) > 0;
        const Vec<2> jump = i_up ? Vec<2>(P.u[i] - P.u[j]) : Vec<2>(P.u[j] - P.u[i]);
        const double w = std::sqrt(rho);
        sn += jump.dot(n) * w, st += jump.dot(t) * w, ss += rho, sum_t += t;
      }
    }
    if (!(ss > 0)) return false;
    // jump = 8 K / E' sqrt(rho / 2 pi)  =>  K = E' sqrt(2 pi) c / 8 with c the fitted slope.
    const double scale = tip.modulus * std::sqrt(2.0 * M_PI) / 8.0;
    KI = scale * sn / ss, KII = scale * st / ss;
    along = sum_t.normalized();
    return true;
  }
}

template <int Dim>
std::size_t TipGrower<Dim>::cut_pairs(const Vec<Dim>& a, const Vec<Dim>& b) {
  if constexpr (Dim != 2) {
    (void)a, (void)b;
    return 0;
  } else {
    auto& N = m_.pairs;
    Vec<2> normal(-(b - a)[1], (b - a)[0]);
    normal.normalize();
    std::size_t count = 0;
    for_pairs_crossing(N, m_.points.x0, a, b, m_.mesh_size, [&](int64_t e, std::size_t i, std::size_t j) {
      if (!N.intact[e]) return false;
      // Both entries of the pair: this one and its mirror in j's list (sorted by partner).
      const auto first = N.partner.begin() + N.offset[j], last = N.partner.begin() + N.offset[j + 1];
      const auto mirror = static_cast<int64_t>(std::lower_bound(first, last, static_cast<int32_t>(i)) - N.partner.begin());
      const auto index = static_cast<int32_t>(N.cut_normal.size() / 2);
      N.cut_normal.push_back(normal[0]), N.cut_normal.push_back(normal[1]);
      for (int64_t f : {e, mirror}) N.intact[f] = 0, N.cut[f] = index;
      ++count;
      return false;
    });
    return count;
  }
}

template <int Dim>
bool TipGrower<Dim>::meets_crack(const GrowingTip<Dim>& tip, const Vec<Dim>& b) const {
  if constexpr (Dim != 2) {
    (void)tip, (void)b;
    return false;
  } else {
    // Pairs cut by the tip's own last advance, or whose middles lie within 1.5 mesh sizes of the tip
    // (the path just behind it: a pair crossing it near the tip reaches ahead), are not a crack met.
    const auto& N = m_.pairs;
    const auto& X = m_.points.x0;
    const double own = 1.5 * m_.mesh_size;
    return for_pairs_crossing(N, X, tip.x, b, m_.mesh_size, [&](int64_t e, std::size_t i, std::size_t j) {
      return !N.intact[e] && !(N.cut[e] >= tip.last_cut && tip.last_cut >= 0) &&
             (0.5 * (X[i] + X[j]) - tip.x).norm() >= own;
    });
  }
}

template <int Dim>
std::size_t TipGrower<Dim>::check(double t) {
  if constexpr (Dim != 2) {
    (void)t;
    return 0;
  } else {
    const auto& g = m_.tip_growth;
    std::size_t cut = 0;
    for (std::size_t k = 0; k < m_.tips.size(); ++k) {
      auto& tip = m_.tips[k];
      if (tip.stop || (tip.last_time >= 0 && t - tip.last_time < g.length / g.max_speed)) continue;
      refresh_near(k);
      double KI = 0, KII = 0;
      Vec<2> along;
      if (!intensities(k, KI, KII, along)) continue;
      // Faces pressed together (K_I <= 0) do not grow: under a compressive load (a Brazilian disc's
      // platens) a sliding tip would otherwise turn on itself.
      if (!(KI > 0.0)) continue;
      const double theta = crack::hoop_stress_angle(KI, KII);
      if (crack::hoop_stress_intensity(KI, KII, theta) < tip.toughness) continue;
      // The direction is decided once the straight run behind the tip fills the fitting window, and
      // taken from that run: a fit that still reads the parent crack behind a fresh kink would turn
      // the tip again by the parent's angle (and a curling path's fit turns it round on itself).
      // Until then the tip grows straight on.
      Vec<2> dir = tip.dir;
      if (tip.run >= g.radius - 0.5 * g.length) {
        dir = std::cos(theta) * along + std::sin(theta) * Vec<2>(-along[1], along[0]);
        tip.run = 0.0;
      }
      tip.run += g.length;
      const Vec<2> next = tip.x + g.length * dir;
      if (tip.growths == 0)
        tip.first_time = t, tip.first_KI = KI, tip.first_KII = KII,
        tip.kink = std::atan2(tip.dir[0] * dir[1] - tip.dir[1] * dir[0], tip.dir.dot(dir));
      const bool meets = meets_crack(tip, next);
      tip.last_cut = static_cast<int32_t>(m_.pairs.cut_normal.size() / 2);
      cut += cut_pairs(tip.x, next);
      tip.x = next, tip.dir = dir, tip.last_time = t, ++tip.growths;
      if (meets) tip.stop = 2;                                                         // a crack (or its own path)
      else if (!particle_within(m_.points.x0, next, 0.75 * m_.mesh_size)) tip.stop = 1;  // it left the bodies
    }
    return cut;
  }
}

template <int Dim>
nlohmann::json TipGrower<Dim>::info() const {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& tip : m_.tips) {
    const bool grew = tip.growths > 0;
    auto or_null = [&](double v) { return grew ? nlohmann::json(v) : nlohmann::json(nullptr); };
    out.push_back({{"crack", tip.crack},
                   {"start_m", as_vector<Dim>(tip.start)},
                   {"end_m", as_vector<Dim>(tip.x)},
                   {"growths", tip.growths},
                   {"K_Ic_Pa_sqrt_m", tip.toughness},
                   {"material", tip.material},
                   {"started_s", or_null(tip.first_time)},
                   {"kink_deg", or_null(tip.kink * 180.0 / M_PI)},
                   {"K_I_at_start_Pa_sqrt_m", or_null(tip.first_KI)},
                   {"K_II_at_start_Pa_sqrt_m", or_null(tip.first_KII)},
                   {"state", tip.stop == 2 ? "reached a crack" : tip.stop == 1 ? "reached an edge" : "inside"}});
  }
  return out;
}

template <int Dim>
void TipGrower<Dim>::save(StateWriter& w) const {
  for (const auto& tip : m_.tips) {
    w.value(tip.x), w.value(tip.dir), w.value(tip.stop), w.value(tip.last_cut), w.value(tip.run), w.value(tip.growths);
    w.value(tip.first_time), w.value(tip.last_time), w.value(tip.kink), w.value(tip.first_KI), w.value(tip.first_KII);
  }
  w.array(m_.pairs.cut), w.array(m_.pairs.cut_normal);
}

template <int Dim>
void TipGrower<Dim>::load(StateReader& r) {
  for (auto& tip : m_.tips) {
    r.value(tip.x), r.value(tip.dir), r.value(tip.stop), r.value(tip.last_cut), r.value(tip.run), r.value(tip.growths);
    r.value(tip.first_time), r.value(tip.last_time), r.value(tip.kink), r.value(tip.first_KI), r.value(tip.first_KII);
  }
  r.array(m_.pairs.cut, "pair entries");
  r.array_sized(m_.pairs.cut_normal, "crack normals", m_.pairs.cut_normal.size(), Dim * m_.pairs.cut.size());
  std::fill(near_at_.begin(), near_at_.end(), Vec<Dim>::Constant(std::numeric_limits<double>::quiet_NaN()));
}

template <int Dim>
void read_tip_growth(const nlohmann::json& section, const std::string& key, const UnitSystem& units,
                     const std::vector<std::vector<Vec<Dim>>>& crack_points, const std::vector<std::string>& crack_names,
                     PemSystem<Dim>& m) {
  const ObjectReader r(section, key, {"radius", "length", "max_speed"});
  if (Dim != 2) throw SceneError(key, "tip growth is 2D only (3D pem cracks grow by pairs breaking)");
  const double L = units.factor(Quantity::Length), h = m.mesh_size;
  auto& g = m.tip_growth;
  g.enabled = true;
  g.radius = r.positive_or("radius", 4.0 * h, L);
  g.length = r.positive_or("length", h, L);
  if (g.radius < 2.0 * h)
    throw SceneError(r.at("radius"), format("at least 2 mesh sizes (%g in the scene's length unit): the jumps are "
                                            "fitted from 1 mesh size behind the tip out to it", 2.0 * h / L));
  if (g.length < 0.25 * h || g.length > 4.0 * h)
    throw SceneError(r.at("length"), "between 0.25 and 4 mesh sizes");
  if (crack_points.empty()) throw SceneError(key, "the scene declares no cracks to grow");
  // The speed cap: the slowest material's Rayleigh speed (network nu; a plate in plane stress passes
  // nu / (1 + nu)), unless given.
  double cap = INFINITY;
  for (const auto& mat : m.materials) {
    const double nu = mat.nu_network, mu = mat.E / (2.0 * (1.0 + nu));
    const double nu_solid = m.analysis == Analysis::PlaneStress ? nu / (1.0 + nu) : nu;
    cap = std::min(cap, crack::rayleigh_speed(mu, mat.density, nu_solid));
  }
  g.max_speed = r.positive_or("max_speed", cap, units.factor(Quantity::Velocity));
  // Tips: the ends of each crack whose short step outwards lies inside the bodies.
  for (std::size_t c = 0; c < crack_points.size(); ++c) {
    const auto& pts = crack_points[c];
    if (pts.size() < 2) continue;
    for (int end = 0; end < 2; ++end) {
      GrowingTip<Dim> tip;
      tip.crack = crack_names[c];
      tip.start = tip.x = end ? pts.back() : pts.front();
      const Vec<Dim> behind = tip.x - (end ? pts[pts.size() - 2] : pts[1]);
      tip.dir = behind.normalized();
      tip.run = behind.norm();
      if (!particle_within(m.points.x0, Vec<Dim>(tip.x + 0.5 * h * tip.dir), 0.75 * h)) continue;
      m.tips.push_back(tip);
      std::size_t nearest = 0;
      for (std::size_t p = 1; p < m.points.x0.size(); ++p)
        if ((m.points.x0[p] - tip.x).squaredNorm() < (m.points.x0[nearest] - tip.x).squaredNorm()) nearest = p;
      const auto& mat = m.materials[m.points.material[nearest]];
      if (!(mat.fracture_energy > 0))
        throw SceneError(key, "the material '" + mat.name + "' at a tip of crack '" + crack_names[c] +
                                  "' gives no fracture_energy: the tips grow when K reaches sqrt(E' G_c)");
      auto& t = m.tips.back();
      const double nu = mat.nu_network;
      t.modulus = m.analysis == Analysis::PlaneStress ? mat.E : mat.E / (1.0 - nu * nu);
      t.toughness = std::sqrt(t.modulus * mat.fracture_energy);
      t.material = mat.name;
    }
  }
  if (m.tips.empty()) throw SceneError(key, "no crack has a tip inside the bodies");
}

template class TipGrower<2>;
template class TipGrower<3>;
template void read_tip_growth<2>(const nlohmann::json&, const std::string&, const UnitSystem&,
                                 const std::vector<std::vector<Vec<2>>>&, const std::vector<std::string>&, PemSystem<2>&);
template void read_tip_growth<3>(const nlohmann::json&, const std::string&, const UnitSystem&,
                                 const std::vector<std::vector<Vec<3>>>&, const std::vector<std::string>&, PemSystem<3>&);

}  // namespace cleave::pem
