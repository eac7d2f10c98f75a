// Growing 2D cracks: the growth check and the new segments (crack_growth.hpp).
#include "libmpm/mpm/crack_growth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libmpm/core/error.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/mpm/material_probe.hpp"

namespace cleave {

namespace {

// Where the segment a -> a + L d (d a unit vector) first meets segment [p, q]: its parameter in
// [0, L], or infinity when it does not.
double ray_hit(const Vec<2>& a, const Vec<2>& d, double L, const Vec<2>& p, const Vec<2>& q) {
  const Vec<2> e = q - p, w = p - a;
  const double den = d.x() * e.y() - d.y() * e.x();
  if (den == 0.0) return INFINITY;  // parallel: a collinear touch is left to the next growth
  const double t = (w.x() * e.y() - w.y() * e.x()) / den, u = (w.x() * d.y() - w.y() * d.x()) / den;
  return t >= 0.0 && t <= L && u >= 0.0 && u <= 1.0 ? t : INFINITY;
}

// The reference-configuration place of a new crack point (crack/reference_side.hpp): the segment
// grown from the tip at angle theta to the tip's direction, grown from the reference tip at theta to
// the reference tip's direction, as long. A crack that grows straight on in the body grows straight
// on there, whatever its current line's drift against the material. (The new point's own reference
// place, to - u(to), would carry that drift, which is what crossed a particle row 1e-4 cell below a
// growing crack; not tried. Mapped back with the material's mean rotation and strain ahead of the tip,
// the near-tip strain turned it: 0.58 cell off its line within 20 cells.)
Vec<2> reference_of(const crack::Crack2D& c, int end, double theta, double length) {
  const std::size_t n = c.reference.size();
  const Vec<2> tip = end == 1 ? c.reference[n - 1] : c.reference[0];
  const Vec<2> prev = end == 1 ? c.reference[n - 2] : c.reference[1];
  const Vec<2> e1 = (tip - prev).normalized(), e2(-e1.y(), e1.x());
  // (e2 as tip_frame's: the left normal of the direction out of the tip)
  return tip + length * (std::cos(theta) * e1 + std::sin(theta) * e2);
}

}  // namespace

CrackGrowth::CrackGrowth(Model<2>& m) : m_(m) {
  for (const auto& p : m.propagation) active_ = active_ || p.has_value();
  if (!active_) return;
  state_.resize(2 * m.cracks.size());
  half_size_ = particle_half_sizes(m);
}

bool CrackGrowth::due(long step, double time) const {
  if (!active_) return false;
  for (const auto& c : m_.cracks) {
    const auto& p = m_.propagation[static_cast<std::size_t>(c.id)];
    if (!p || step % p->check_interval != 0) continue;
    for (int end = 0; end < 2; ++end) {
      const TipState& st = state_[2 * c.id + end];
      if (c.tip[end] && (st.last_time < 0.0 || time - st.last_time >= st.wait)) return true;
    }
  }
  return false;
}

bool CrackGrowth::grow(double time, long step, const std::vector<crack::TipRecord>& tips,
                       std::vector<std::string>& warnings) {
  const double h = m_.grid.h;
  bool changed = false;
  for (const crack::TipRecord& rec : tips) {
    const auto& prop = m_.propagation[static_cast<std::size_t>(rec.crack)];
    auto& c = m_.cracks[static_cast<std::size_t>(rec.crack)];
    if (!prop || step % prop->check_interval != 0 || !c.tip[rec.end]) continue;
    TipState& st = state_[2 * rec.crack + rec.end];
    const Material<2>& mat = *m_.materials[static_cast<std::size_t>(rec.material)];  // the tip's nearest particle's
    double mu = 0.0, nu = 0.0;
    mat.isotropic_elastic(mu, nu);  // checked by the scene reader for every growing crack's body
    crack::TipLoading t;
    t.J = rec.J1, t.KI = rec.KI, t.KII = rec.KII;
    t.e_prime = 8.0 * mu / (crack::kolosov_kappa(m_.analysis, nu) + 1.0);
    const double f = prop->resistance_factor(st.grown);  // K_R / K_Ic
    const double KIc = mat.toughness_KIc() > 0.0 ? mat.toughness_KIc() : std::sqrt(mat.toughness_Gc() * t.e_prime);
    t.KIc = f * KIc;
    t.Gc = t.KIc * t.KIc / t.e_prime;
    const double ratio = crack::InitiationCriteria::instance().at(prop->criterion)(t);
    if (!(ratio >= 1.0)) continue;
    const double da = prop->growth_length * h;
    const double nu_solid = m_.analysis == Analysis::PlaneStress ? nu / (1.0 + nu) : nu;
    const double wait = da * (1.0 - 1e-12) / (prop->max_speed_cR * crack::rayleigh_speed(mu, mat.density(), nu_solid));
    if (st.last_time >= 0.0 && time - st.last_time < wait) continue;  // too soon after the last growth
    const double theta = crack::DirectionRules::instance().at(prop->direction)(t);
    const crack::TipFrame fr = crack::tip_frame(c, rec.end);
    const Vec<2> dir = std::cos(theta) * fr.e1 + std::sin(theta) * fr.e2;
    Vec<2> to = fr.tip + da * dir;
    GrowthStop stop = GrowthStop::None;

    // A crack within a cell past the new point: join it there (a ligament under a cell would tie the
    // faces through the nodes its particles share). The tip's own segment is skipped.
    double hit = INFINITY;
    const std::size_t n = c.points.size();
    for (const auto& o : m_.cracks)
      for (std::size_t s = 0; s + 1 < o.points.size(); ++s) {
        if (&o == &c && (rec.end == 1 ? s + 2 == n : s == 0)) continue;
        hit = std::min(hit, ray_hit(fr.tip, dir, da + h, o.points[s], o.points[s + 1]));
      }
    if (hit <= da + h) {
      to = fr.tip + (hit + 0.02 * h) * dir;  // just past it, so that the two cut the material through
      stop = GrowthStop::OtherCrack;
    } else {
      // Under a cell of material ahead: carried through the free edge, as the scene reader does. The
      // rows either side of a crack between particle rows sit half a spacing off its line and move
      // apart as it opens: a quarter cell of slack keeps them ahead of it.
      const double edge = material_ahead(m_, half_size_, to, dir, Vec<2>(-dir.y(), dir.x()), 2.0 * h, 0.25 * h);
      if (edge < h - 1e-9 * h) to += (edge + 0.5 * h) * dir, stop = GrowthStop::FreeEdge;
    }
    const Vec<2> lo = m_.grid.origin, hi = m_.grid.upper();
    if (!((to.array() > lo.array() + h).all() && (to.array() < hi.array() - h).all())) {
      warnings.push_back(format("crack '%s': its %s tip stopped growing at t = %.6g s: its next point ", c.name.c_str(),
                                rec.end ? "end" : "start", time) +
                         position_text<2>(to) + " lies within a cell of the grid's edge; enlarge the grid");
      c.tip[rec.end] = 0;
      events_.push_back({time, rec.crack, rec.end, fr.tip, 0.0, 0.0, theta, rec.J1, rec.KI, rec.KII, ratio,
                         GrowthStop::GridEdge});
      changed = true;
      continue;
    }
    const double length = (to - fr.tip).norm();
    if (c.reference.size() != c.points.size()) c.reference = c.points;  // (a crack built without one)
    const Vec<2> X_to = reference_of(c, rec.end, theta, length);
    if (rec.end == 1) {
      c.points.push_back(to), c.above.push_back(to), c.below.push_back(to), c.reference.push_back(X_to);
    } else {
      c.points.insert(c.points.begin(), to), c.above.insert(c.above.begin(), to), c.below.insert(c.below.begin(), to);
      c.reference.insert(c.reference.begin(), X_to);
    }
    crack::set_polyline_segments(c);
    if (stop != GrowthStop::None) c.tip[rec.end] = 0, c.cut_end[rec.end] = 0;  // through an edge, or into a crack
    c.update_extent();
    st.grown += length;
    st.last_time = time;
    st.wait = wait;
    st.t[st.count % kHistory] = time, st.s[st.count % kHistory] = st.grown;
    ++st.count;
    // The speed since the newest growth at least kSpeedCells behind (or the oldest kept).
    double speed = 0.0;
    for (long k = st.count - 2; k >= 0 && k >= st.count - kHistory; --k) {
      const int i = static_cast<int>(k % kHistory);
      if (time > st.t[i]) speed = (st.grown - st.s[i]) / (time - st.t[i]);
      if (st.grown - st.s[i] >= kSpeedCells * h * (1.0 - 1e-9)) break;
    }
    events_.push_back({time, rec.crack, rec.end, to, length, speed, theta, rec.J1, rec.KI, rec.KII, ratio, stop});
    changed = true;
  }
  return changed;
}

std::vector<GrowthEvent> CrackGrowth::take_events() {
  std::vector<GrowthEvent> e;
  e.swap(events_);
  return e;
}

std::vector<std::string> CrackGrowth::columns() {
  return {"time_s", "crack", "tip", "x_m", "y_m", "length_m", "speed_m_per_s", "kink_rad",
          "J1_J_per_m2", "KI_Pa_sqrt_m", "KII_Pa_sqrt_m", "criterion_ratio", "stop"};
}

std::vector<double> CrackGrowth::row(const GrowthEvent& e) {
  return {e.time, double(e.crack), double(e.tip), e.to.x(), e.to.y(), e.length, e.speed, e.angle,
          e.J,    e.KI,            e.KII,         e.ratio,  double(static_cast<int>(e.stop))};
}

void CrackGrowth::save(StateWriter& w) const {
  w.array(state_);
  for (const auto& c : m_.cracks) w.array(c.tip), w.array(c.cut_end);
}

void CrackGrowth::load(StateReader& r) {
  r.array(state_, "crack growth states");
  for (auto& c : m_.cracks) {
    r.array(c.tip, "crack tips"), r.array(c.cut_end, "crack tips");
    crack::set_polyline_segments(c);
    c.update_extent();  // (the cut polyline follows cut_end)
  }
  events_.clear();
}

}  // namespace cleave
