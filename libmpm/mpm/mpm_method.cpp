// The Material Point Method behind the method seam (method/method.hpp): the model built from the
// scene (mpm_scene.cpp), the stepper (mpm_step.cpp), and what a run writes: particle frames, crack
// frames, global.csv columns, crack_tips.csv rows and the restart state.
#include <cmath>
#include <optional>
#include <cstdio>
#include <sstream>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/io/crack_output.hpp"
#include "libmpm/mpm/crack_growth.hpp"
#include "libmpm/mpm/particle_output.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/method/relaxation.hpp"
#include "libmpm/method/tip_table.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/mpm/mpm_step.hpp"

namespace cleave {
namespace {

// One line per declared pair of bodies in contact (the scene's "contact").
template <int Dim>
void describe_body_contact(const Model<Dim>& m, std::vector<std::string>& out) {
  const BodyContact& bc = m.body_contact;
  if (!bc.active()) return;
  for (std::size_t a = 0; a < m.bodies.size(); ++a)
    for (std::size_t b = a + 1; b < m.bodies.size(); ++b) {
      if (bc.group[a] == bc.group[b]) continue;
      const crack::ContactSettings* c = bc.law(bc.group[a], bc.group[b]);
      if (!c) continue;
      const std::string law = std::string(crack::contact_law_name(c->contact_law)) +
                              (c->contact_law == crack::ContactLaw::Friction ? format(" mu=%g", c->friction) : "");
      out.push_back(format("contact '%s' - '%s': %s, %s", m.bodies[a].name.c_str(), m.bodies[b].name.c_str(),
                           law.c_str(),
                           c->detection == crack::Detection::Volume
                               ? format("volume detection (v_sep %g, v_contact %g)", c->v_sep, c->v_contact).c_str()
                               : format("position detection (d_contact %g cells)", c->d_contact).c_str()));
    }
}

template <int Dim>
class MpmMethod final : public Method<Dim> {
 public:
  explicit MpmMethod(const nlohmann::json& scene)
      : owned_(std::make_unique<Model<Dim>>(build_model<Dim>(scene))), m_(*owned_), stepper_(make_stepper<Dim>(m_)) {
    if (m_.static_tolerance > 0) relax_.emplace(m_.static_tolerance);
    make_growth();
  }
  // A method over a model the caller built and keeps (tests and benchmarks inspect it afterwards).
  explicit MpmMethod(Model<Dim>& m) : m_(m), stepper_(make_stepper<Dim>(m_)) {
    if (m_.static_tolerance > 0) relax_.emplace(m_.static_tolerance);
    make_growth();
  }

  const char* name() const override { return "mpm"; }
  const RunSettings& settings() const override { return m_; }
  std::pair<double, std::string> work_per_step() const override { return {double(m_.particles.size()), "particle"}; }

  std::vector<std::string> describe() const override {
    const Model<Dim>& m = m_;
    std::vector<std::string> out;
    out.push_back(format("%s%dD %s, %zu particles in %zu bodies, %zu materials",
                         m.title.empty() ? "" : (m.title + ": ").c_str(), Dim,
                         analysis_name(m.analysis),
                         m.particles.size(), m.bodies.size(), m.materials.size()));
    std::string grid = format("grid: cell %.6g m, %zu nodes", m.grid.h, m.grid.node_count());
    for (int d = 0; d < Dim; ++d) grid += format("%s%d", d ? " x " : " (", m.grid.nodes[d]);
    out.push_back(grid + ")");
    out.push_back(format("method: MPM, %s, %s; dt = %.6g s (stable limit %.6g s), %ld steps to %.6g s",
                         m.shape_function == ShapeFunctionKind::UGimp ? "uGIMP" : "linear", scheme_name(m.scheme), m.dt,
                         m.stable_dt, static_cast<long>(std::ceil(m.end_time / m.dt - 1e-9)), m.end_time));
    describe_static(m, out);
    for (const auto& c : m.cracks)
      out.push_back(format("crack '%s': %s, contact %s%s, %s detection", c.name.c_str(), crack_size(c).c_str(),
                           crack::contact_law_name(c.contact_law),
                           c.contact_law == crack::ContactLaw::Friction
                               ? (" mu=" + std::to_string(c.friction)).c_str() : "",
                           c.detection == crack::Detection::Volume ? "volume" : "displacement"));
    if constexpr (Dim == 2)
      for (const auto& c : m.cracks)
        if (const auto& p = m.propagation.empty() ? std::nullopt : m.propagation[c.id])
          out.push_back(format("crack '%s' grows: %s criterion, %s direction, %.3g-cell steps, checked every %d step%s%s",
                               c.name.c_str(), p->criterion.c_str(), p->direction.c_str(), p->growth_length,
                               p->check_interval, p->check_interval == 1 ? "" : "s",
                               format(", speed at most %.3g c_R", p->max_speed_cR).c_str()) +
                        "; crack_growth.csv");
    describe_body_contact(m, out);
    out.push_back(format("output: every %.6g s (%zu fields), global.csv every %.6g s", m.output.interval,
                         m.output.fields.size(), m.output.global_interval));
    if (m.crack_tips) {
      int tips = 0;
      std::size_t nodes = 0;
      for (const auto& c : m.cracks)
        if constexpr (Dim == 3) {
          for (std::size_t f = 0; f < c.fronts.size(); ++f)
            if (c.tip[f]) ++tips, nodes += c.fronts[f].nodes.size();
        } else {
          tips += c.tip[0] + c.tip[1];
        }
      const auto& t = *m.crack_tips;
      if (Dim == 3 && t.integral == crack::TipSettings::Integral::Domain)
        out.push_back(format("crack fronts: %d, %zu nodes, J1 by the domain integral%s over a tube of %.6g cells "
                             "(weight 1 within %.6g cells, along the front %.6g cells), J2 and the openings from the "
                             "contour, %s every %.6g s",
                             tips, nodes, t.volume_term ? " with inertia (eq. 33)" : " without inertia (eq. 32)", t.radius,
                             t.inner * t.radius, t.along, this->tip_file().c_str(), m.output.tip_interval));
      else
        out.push_back(format("%s, J by %s on a %s of %.6g cells (%d points), %s every %.6g s",
                             Dim == 3 ? format("crack fronts: %d, %zu nodes", tips, nodes).c_str()
                                      : format("crack tips: %d", tips).c_str(),
                             (std::string(t.volume_term ? "eq. 33 (contour + volume)" : "eq. 32 (contour)") +
                              (Dim == 3 && t.out_of_plane_term ? " less the out-of-plane term" : "")).c_str(),
                             t.contour == crack::TipSettings::Contour::Circle ? "circle" : "square", t.radius, t.points,
                             this->tip_file().c_str(), m.output.tip_interval));
      for (const auto& r : m.front_references)
        out.push_back(format("reference: crack '%s' as an embedded %s in an infinite body, %.6g Pa along (%.3g, %.3g, "
                             "%.3g)", m.cracks[r.crack].name.c_str(), r.a == r.b ? "circle" : "ellipse", r.stress,
                             r.load_axis.x(), r.load_axis.y(), r.load_axis.z()));
    }
    return out;
  }

  static std::string crack_size(const crack::ExplicitCrack<Dim>& c) {
    if constexpr (Dim == 3) {
      int tips = 0;
      for (auto t : c.tip) tips += t;
      return format("%zu triangles, %zu points, %zu fronts (%d tips)", c.simplices.size(), c.points.size(),
                    c.fronts.size(), tips);
    } else {
      return format("%zu segments", c.points.size() - 1);
    }
  }

  StepProblem step() override {
    StepProblem p = stepper_->step();
    if constexpr (Dim == 2)
      if (growth_ && growth_->due(stepper_->step_count(), stepper_->time())) grow_cracks();
    if (relax_ && relax_->due(stepper_->step_count())) {
      const auto g = stepper_->global_state();
      m_.damping = relax_->check(g.time, g.strain, g.kinetic, m_.particles);
    }
    if (p) p.what = "particle " + std::to_string(p.particle) + " at " + position_text<Dim>(m_.particles.x[p.particle]) +
                    " " + p.what;
    return p;
  }
  double time() const override { return stepper_->time(); }
  long step_count() const override { return stepper_->step_count(); }
  std::string take_warning() override {
    std::string w = stepper_->take_warning();
    for (const auto& g : growth_warnings_) w += (w.empty() ? "" : "\n") + g;
    growth_warnings_.clear();
    return w;
  }
  std::string fastest_point() const override {
    const auto& P = m_.particles;
    const std::size_t fast = fastest<Dim>(P.v);
    std::ostringstream s;
    s << "particle " << fast << " at " << position_text<Dim>(P.x[fast]) << ", speed " << P.v[fast].norm() << " m/s";
    return s.str();
  }

  bool static_reached() const override { return relax_ && relax_->reached(); }
  std::string relaxation_state() const override { return relax_ ? relax_->state() : std::string(); }
  nlohmann::json run_info() const override {
    nlohmann::json j = nlohmann::json::object();
    if (relax_)
      j["static"] = {{"tolerance", relax_->tolerance()}, {"reached", relax_->reached()},
                     {"lowest_mode_rad_per_s", relax_->omega()}, {"damping_per_s", relax_->kappa()}};
    return j;
  }

  std::vector<std::string> global_columns() const override {
    // Names carry their SI unit (docs/scenes.md, "Output files").
    std::vector<std::string> c = {"time_s", "step", "kinetic_energy_J", "strain_energy_J", "external_work_J",
                                  "total_energy_J", "momentum_x_kg_m_per_s", "momentum_y_kg_m_per_s"};
    if (Dim == 3) c.push_back("momentum_z_kg_m_per_s");
    return c;
  }
  GlobalRow global_row() const override {
    const auto g = stepper_->global_state();
    GlobalRow r;
    r.values = {g.time, double(g.step), g.kinetic, g.strain, g.external_work, g.total()};
    for (int d = 0; d < Dim; ++d) r.values.push_back(g.momentum[d]);
    r.total_energy = g.total();
    r.external_work = g.external_work;
    return r;
  }

  std::vector<std::string> frame_series() const override {
    if (m_.cracks.empty()) return {"particles"};
    return {"particles", "cracks"};
  }
  io::PointSet frame(std::size_t series) override {
    if (series == 0) return particle_point_set<Dim>(m_, m_.output.fields);
    if constexpr (Dim == 3) {
      if (m_.crack_tips) return io::crack_point_set(m_.cracks, fronts_now());
    } else {
      if (m_.crack_tips) return io::crack_point_set(m_.cracks, tips_now());
    }
    return io::crack_point_set(m_.cracks);
  }

  std::string event_file() const override { return "crack_growth.csv"; }
  std::vector<std::string> event_columns() const override {
    return growth_ ? CrackGrowth::columns() : std::vector<std::string>{};
  }
  std::vector<std::vector<double>> take_event_rows() override {
    std::vector<std::vector<double>> rows;
    if (growth_)
      for (const auto& e : growth_->take_events()) rows.push_back(CrackGrowth::row(e));
    return rows;
  }

  std::string tip_file() const override { return Dim == 3 ? "crack_fronts.csv" : "crack_tips.csv"; }
  std::size_t tip_rows_per_record() const override {
    std::size_t n = 0;
    for (const auto& c : m_.cracks)
      if constexpr (Dim == 3) {
        for (std::size_t f = 0; f < c.fronts.size(); ++f) n += c.tip[f] ? c.fronts[f].nodes.size() : 0;
      } else {
        n += c.tip[0] + c.tip[1];
      }
    return n;
  }
  std::vector<std::string> tip_columns() const override {
    if (!m_.crack_tips) return {};
    if constexpr (Dim == 3) {
      // crack_fronts.csv (docs/scenes.md, "Output files"): one row per front node per record.
      std::vector<std::string> c = {"time_s", "crack", "front", "node", "s_m", "x_m", "y_m", "z_m",
                                    "J1_J_per_m2", "J2_J_per_m2", "KI_Pa_sqrt_m", "KII_Pa_sqrt_m", "KIII_Pa_sqrt_m",
                                    "flag"};
      if (!m_.front_references.empty())
        c.insert(c.end(), {"phi_rad", "KI_ref_Pa_sqrt_m", "KII_ref_Pa_sqrt_m", "KIII_ref_Pa_sqrt_m"});
      return c;
    }
    return table_.columns();
  }
  std::vector<std::vector<double>> tip_rows() override {
    std::vector<std::vector<double>> rows;
    if (!m_.crack_tips) return rows;
    const double t = stepper_->time();
    if constexpr (Dim == 3) {
      for (const auto& r : fronts_now()) {
        std::vector<double> row = {t,       double(r.crack), double(r.front), double(r.node), r.s, r.x.x(), r.x.y(),
                                   r.x.z(), r.J1,            r.J2,            r.KI,           r.KII, r.KIII, double(r.flag)};
        if (!m_.front_references.empty()) {
          const crack::FrontFrame f = crack::front_frame(m_.cracks[r.crack], r.front, r.node);
          const crack::EllipseReference* ref = nullptr;
          for (const auto& e : m_.front_references)
            if (e.crack == r.crack) ref = &e;
          if (ref) {
            const auto k = ref->at(f);
            row.insert(row.end(), {ref->phi(f.x), k.KI, k.KII, k.KIII});
          } else {
            row.insert(row.end(), 4, std::nan(""));
          }
        }
        rows.push_back(std::move(row));
      }
      return rows;
    }
    for (const auto& r : tips_now()) {
      Vec<Dim> x = Vec<Dim>::Zero();  // tips are of 2D cracks (the only explicit cracks built so far)
      x.template head<2>() = r.x;
      rows.push_back(table_.row(t, r.crack, r.end, x, {r.J1, r.J2, r.KI, r.KII}));
    }
    return rows;
  }

  void save(StateWriter& w) const override {
    stepper_->sync_strain();
    w.value(stepper_->time());
    w.value(stepper_->step_count());
    w.value(stepper_->external_work());
    const auto& P = m_.particles;
    w.array(P.x), w.array(P.v), w.array(P.u), w.array(P.stress), w.array(P.strain), w.array(P.rotation);
    if (!P.rotation3.empty()) w.array(P.rotation3);  // 3D with crack-front parameters only
    for (const auto& c : m_.cracks) w.array(c.points), w.array(c.above), w.array(c.below), w.array(c.reference);
    table_.save(w);
    if (relax_) relax_->save(w);
    if (growth_) growth_->save(w);
  }
  void load(StateReader& r) override {
    double t = 0, work = 0;
    long step = 0;
    r.value(t), r.value(step), r.value(work);
    tips_step_ = fronts_step_ = -1;  // the state changes under the caches
    auto& P = m_.particles;
    r.array(P.x, "particles"), r.array(P.v, "particles"), r.array(P.u, "particles");
    r.array(P.stress, "particles"), r.array(P.strain, "particles"), r.array(P.rotation, "particle rotations");
    if (!P.rotation3.empty()) r.array(P.rotation3, "particle rotations");
    for (auto& c : m_.cracks) {
      if (growth_) {  // a growing crack's points: as many as it had grown to
        r.array_sized(c.points, "crack points", 2, std::size_t(1) << 28);
        r.array_sized(c.above, "crack points", c.points.size(), c.points.size());
        r.array_sized(c.below, "crack points", c.points.size(), c.points.size());
        r.array_sized(c.reference, "crack points", c.points.size(), c.points.size());
      } else {
        r.array(c.points, "crack points"), r.array(c.above, "crack points"), r.array(c.below, "crack points");
        r.array(c.reference, "crack points");
      }
      c.update_extent();
    }
    table_.load(r);
    if (relax_) relax_->load(r), m_.damping = relax_->kappa();
    if (growth_) growth_->load(r);
    stepper_->restore(t, step, work);
  }


 private:
  void make_growth() {
    if constexpr (Dim == 2) {
      auto g = std::make_unique<CrackGrowth>(m_);
      if (g->active()) growth_ = std::move(g);
    }
  }
  // The growth check after a step: J and K at the tips (the scene's crack_tips contour, or the
  // default one), then the growth. When nothing grew, the same evaluation serves this step's output.
  void grow_cracks() {
    if constexpr (Dim == 2) {
      costs::Scope cost(costs::CrackGrowth);
      const crack::TipSettings ts = m_.crack_tips ? *m_.crack_tips : crack::TipSettings{};
      std::vector<crack::TipRecord> tips = stepper_->crack_tip_parameters(ts);
      if (growth_->grow(stepper_->time(), stepper_->step_count(), tips, growth_warnings_)) {
        tips_step_ = -1;
      } else if (m_.crack_tips) {
        tips_ = std::move(tips);
        tips_step_ = stepper_->step_count();
      }
    }
  }

  // J and K at the tips in the current state: a frame (cracks.vtu) and a crack_tips.csv row at the
  // same step share one evaluation of the contours (charged to J/K in the run's costs).
  const std::vector<crack::TipRecord>& tips_now() {
    if (tips_step_ != stepper_->step_count()) {
      costs::Scope cost(costs::TipParameters);
      tips_ = stepper_->crack_tip_parameters(*m_.crack_tips);
      tips_step_ = stepper_->step_count();
    }
    return tips_;
  }

  // The same for 3D fronts.
  const std::vector<crack::FrontRecord>& fronts_now() {
    if (fronts_step_ != stepper_->step_count()) {
      costs::Scope cost(costs::TipParameters);
      fronts_ = stepper_->crack_front_parameters(*m_.crack_tips);
      fronts_step_ = stepper_->step_count();
    }
    return fronts_;
  }

  std::unique_ptr<Model<Dim>> owned_;  // null when the caller owns the model
  Model<Dim>& m_;
  std::unique_ptr<Stepper<Dim>> stepper_;
  std::vector<crack::TipRecord> tips_;
  TipTable<Dim> table_{m_.cracks.size(), 2,
                       {"J1_J_per_m2", "J2_J_per_m2", "KI_Pa_sqrt_m", "KII_Pa_sqrt_m"}};  // crack_tips.csv; 2D: two ends
  long tips_step_ = -1;  // step of tips_; -1: none yet
  std::vector<crack::FrontRecord> fronts_;
  long fronts_step_ = -1;
  std::optional<Relaxation> relax_;  // scenes with "static"
  std::unique_ptr<CrackGrowth> growth_;  // 2D scenes whose cracks grow
  std::vector<std::string> growth_warnings_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Method<Dim>> make_mpm_method(Model<Dim>& m) {
  return std::make_unique<MpmMethod<Dim>>(m);
}
template std::unique_ptr<Method<2>> make_mpm_method<2>(Model<2>&);
template std::unique_ptr<Method<3>> make_mpm_method<3>(Model<3>&);

}  // namespace cleave

CLEAVE_REGISTER_METHOD("mpm", cleave::MpmMethod)
