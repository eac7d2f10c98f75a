// Bond-based peridynamics behind the method seam (method/method.hpp), registered as
// "peridynamics": the lattice built from the scene (pd_scene.cpp), the velocity-Verlet solver
// (pd_solver.cpp), and what a run writes: point frames (displacement, velocity, damage, stress
// estimated from bond forces, ...), global.csv (energies, works, broken bonds), crack_tips.csv
// (time, crack, tip, x, y[, z], speed: crack = the tracker's index, tip = 0) and the restart state;
// run.json records the first detected branching of a 2D crack.
#include "libmpm/pd/pd_method.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/io/point_set_builder.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/method/relaxation.hpp"
#include "libmpm/method/tip_table.hpp"
#include "libmpm/io/point_set.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/pd/pd_solver.hpp"
#include "libmpm/pd/tips.hpp"

namespace cleave::pd {

template <int Dim>
io::PointSet pd_point_set(const PdSystem<Dim>& m, const PdSolver<Dim>& s) {
  const auto& P = m.points;
  // Current positions, as for MPM particles (the renderer draws the deformed body).
  io::PointSetBuilder<Dim> b(m.output.fields, P.size(), [&](std::size_t p) { return Vec<Dim>(P.x0[p] + P.u[p]); });
  std::vector<Sym<Dim>> sig;
  if (b.wants_stress()) sig = s.stress();
  std::vector<double> phi;
  if (b.wants("damage")) phi = s.damage();
  b.add_vectors("displacement", P.u);
  b.add_vectors("velocity", P.v);
  b.add_scalars("damage", [&](std::size_t p) { return phi[p]; });
  b.add_scalars("material", [&](std::size_t p) { return double(P.material[p]); });
  b.add_scalars("volume", [&](std::size_t p) { return P.volume[p]; });
  b.add_scalars("size", [&](std::size_t) { return m.dx; });  // each point's lattice cell
  b.add_stress([&](std::size_t p) { return sig[p]; });
  return b.take();
}

template io::PointSet pd_point_set<2>(const PdSystem<2>&, const PdSolver<2>&);
template io::PointSet pd_point_set<3>(const PdSystem<3>&, const PdSolver<3>&);

namespace {

template <int Dim>
class PdMethod final : public Method<Dim> {
 public:
  explicit PdMethod(const nlohmann::json& scene)
      : owned_(std::make_unique<PdSystem<Dim>>(build_pd_system<Dim>(scene))), m_(*owned_), solver_(m_) {
    if (m_.static_tolerance > 0) relax_.emplace(m_.static_tolerance);
  }
  explicit PdMethod(PdSystem<Dim>& m) : m_(m), solver_(m_) {
    if (m_.static_tolerance > 0) relax_.emplace(m_.static_tolerance);
  }

  const char* name() const override { return "peridynamics"; }
  const RunSettings& settings() const override { return m_; }
  std::pair<double, std::string> work_per_step() const override { return {double(m_.bond_count), "bond"}; }

  std::vector<std::string> describe() const override {
    const auto& m = m_;
    const auto& k = m.materials[0].k;
    std::vector<std::string> out = {format("%s%dD %s, peridynamics: %zu points in %zu bodies, %zu bonds (%zu removed by pre-cracks)",
                   m.title.empty() ? "" : (m.title + ": ").c_str(), Dim,
                   analysis_name(m.analysis),
                   m.points.size(), m.bodies.size(), m.bond_count, m.precrack_bonds),
            format("lattice: dx = %.6g m, horizon = %d dx = %.6g m; %s: c = %.6g, s0 = %.6g, implied nu = %.4g", m.dx,
                   m.horizon_factor, m.delta, m.materials[0].name.c_str(), k.c, k.s0, k.implied_nu),
            format("dt = %.6g s (stable limit, seed 003 eq. 15: %.6g s), %ld steps to %.6g s", m.dt, m.stable_dt,
                   static_cast<long>(std::ceil(m.end_time / m.dt - 1e-9)), m.end_time),
            format("output: every %.6g s (%zu fields), global.csv every %.6g s, crack_tips.csv every %.6g s "
                   "(%zu trackers)",
                   m.output.interval, m.output.fields.size(), m.output.global_interval, m.output.tip_interval,
                   m.trackers.size())};
    describe_static(m, out);
    return out;
  }

  StepProblem step() override {
    solver_.step();
    if (relax_ && relax_->due(solver_.step_count())) {
      const auto g = solver_.global_state();
      m_.damping = relax_->check(g.time, g.strain, g.kinetic, m_.points);
    }
    return {};
  }
  bool static_reached() const override { return relax_ && relax_->reached(); }
  std::string relaxation_state() const override { return relax_ ? relax_->state() : std::string(); }
  double time() const override { return solver_.time(); }
  long step_count() const override { return solver_.step_count(); }
  std::string fastest_point() const override {
    const auto& P = m_.points;
    const std::size_t fast = fastest<Dim>(P.v);
    std::ostringstream s;
    s << "point " << fast << " at " << position_text<Dim>(P.x0[fast] + P.u[fast]) << ", speed " << P.v[fast].norm()
      << " m/s";
    return s.str();
  }

  std::vector<std::string> global_columns() const override {
    // Names carry their SI unit (docs/scenes.md, "Output files").
    std::vector<std::string> c = {"time_s", "step", "kinetic_energy_J", "strain_energy_J", "external_work_J",
                                  "damping_loss_J", "total_energy_J", "broken_bonds", "momentum_x_kg_m_per_s",
                                  "momentum_y_kg_m_per_s"};
    if (Dim == 3) c.push_back("momentum_z_kg_m_per_s");
    return c;
  }
  GlobalRow global_row() const override {
    const auto g = solver_.global_state();
    GlobalRow r;
    r.values = {g.time, double(g.step), g.kinetic, g.strain, g.external_work, g.damping_loss, g.total(), double(g.broken)};
    for (int d = 0; d < Dim; ++d) r.values.push_back(g.momentum[d]);
    r.total_energy = g.total();
    r.external_work = g.external_work;
    return r;
  }

  std::vector<std::string> frame_series() const override { return {"particles"}; }
  io::PointSet frame(std::size_t) override { return pd_point_set<Dim>(m_, solver_); }

  std::vector<std::string> tip_columns() const override { return tips_.columns(); }
  // The tracked tips now; the first branching of a 2D crack is recorded for run.json.
  std::vector<std::vector<double>> tip_rows() override {
    const costs::Scope cost(costs::TipTracking);
    std::vector<std::vector<double>> rows;
    const auto phi = solver_.damage();
    const double t = solver_.time();
    for (std::size_t k = 0; k < m_.trackers.size(); ++k)
      if (const auto tip = find_tip<Dim>(m_, phi, m_.trackers[k], m_.tip_threshold))
        rows.push_back(tips_.row(t, k, 0, m_.points.x0[*tip], {}));
    if constexpr (Dim == 2) {
      if (branch_.time < 0) {
        // Only columns ahead of the pre-cracks' damaged band at t = 0 can show a fork.
        if (auto b = find_branch(m_, phi, -std::numeric_limits<double>::infinity(), m_.tip_threshold))
          branch_ = {t, b->x, b->y};
      }
    }
    return rows;
  }
  nlohmann::json run_info() const override {
    nlohmann::json j;
    nlohmann::json names = nlohmann::json::array();
    for (const auto& t : m_.trackers) names.push_back(t.name);
    j["crack_tip_trackers"] = names;  // crack_tips.csv "crack" = index into this list
    if (branch_.time >= 0) j["branching"] = {{"time", branch_.time}, {"x", branch_.x}, {"y", branch_.y}};
    else j["branching"] = nullptr;
    if (relax_)
      j["static"] = {{"tolerance", relax_->tolerance()}, {"reached", relax_->reached()},
                     {"lowest_mode_rad_per_s", relax_->omega()}, {"damping_per_s", relax_->kappa()}};
    return j;
  }

  void save(StateWriter& w) const override {
    w.value(solver_.time()), w.value(solver_.step_count());
    w.value(solver_.external_work()), w.value(solver_.damping_loss());
    w.value(branch_);
    const auto& P = m_.points;
    w.array(P.u), w.array(P.v), w.array(P.a), w.array(m_.nb.intact);
    tips_.save(w);
    if (relax_) relax_->save(w);
  }
  // The solver computed the initial accelerations when it was built; they are replaced by the
  // saved ones (bit-identical continuation) together with u, v and the bond states.
  void load(StateReader& r) override {
    double t = 0, work = 0, damp = 0;
    long step = 0;
    r.value(t), r.value(step), r.value(work), r.value(damp);
    r.value(branch_);
    auto& P = m_.points;
    r.array(P.u, "points"), r.array(P.v, "points"), r.array(P.a, "points"), r.array(m_.nb.intact, "bonds");
    tips_.load(r);
    if (relax_) relax_->load(r), m_.damping = relax_->kappa();
    solver_.restore(t, step, work, damp);
  }

 private:
  struct Branch {
    double time = -1.0, x = 0.0, y = 0.0;
  };
  std::unique_ptr<PdSystem<Dim>> owned_;  // null when the caller owns the system
  PdSystem<Dim>& m_;
  PdSolver<Dim> solver_;
  std::optional<Relaxation> relax_;  // scenes with "static"
  TipTable<Dim> tips_{m_.trackers.size(), 1, {}};  // a tracker follows one tip
  Branch branch_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Method<Dim>> make_pd_method(PdSystem<Dim>& m) {
  return std::make_unique<PdMethod<Dim>>(m);
}
template std::unique_ptr<Method<2>> make_pd_method<2>(PdSystem<2>&);
template std::unique_ptr<Method<3>> make_pd_method<3>(PdSystem<3>&);

}  // namespace cleave::pd

CLEAVE_REGISTER_METHOD("peridynamics", cleave::pd::PdMethod)
