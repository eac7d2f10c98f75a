// The particle equilibrium method behind the method seam (method/method.hpp), registered as "pem":
// the model built from the scene (pem_scene.cpp), the solver (pem_solver.cpp), and what a run writes:
// particle frames (displacement, velocity, damage, pair-force stress, ...), crack frames traced
// through the broken pairs (crack_trace.hpp), global.csv (energies, works, broken pairs, residual
// force, largest speed) and the restart state. The run ends at equilibrium ("pem.equilibrium":
// speed and residual under their tolerances for a number of checks in a row), when the body
// separates into pieces, at the static state of a "static" scene, or at time.end; run.json says which.
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/io/point_set_builder.hpp"
#include "libmpm/method/describe.hpp"
#include "libmpm/method/method.hpp"
#include "libmpm/method/relaxation.hpp"
#include "libmpm/pem/crack_trace.hpp"
#include "libmpm/pem/pem_scene.hpp"
#include "libmpm/pem/pem_solver.hpp"
#include "libmpm/pem/tip_growth.hpp"

namespace cleave::pem {
namespace {

// Components of the intact-pair graph holding at least `least` particles (union-find, path halving).
std::size_t pieces(const PemPairs& N, std::size_t n, std::size_t least) {
  std::vector<int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e)
      if (N.intact[e] && N.k[e] > 0) {
        const int32_t a = find(int32_t(i)), b = find(N.partner[e]);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
  std::vector<std::size_t> count(n, 0);
  for (std::size_t i = 0; i < n; ++i) ++count[find(int32_t(i))];
  std::size_t big = 0;
  for (std::size_t c : count) big += c >= least ? 1 : 0;
  return big;
}

template <int Dim>
class PemMethod final : public Method<Dim> {
 public:
  explicit PemMethod(const nlohmann::json& scene)
      : m_(build_pem_system<Dim>(scene)), solver_(m_), tracer_(m_) {
    if (m_.static_tolerance > 0) relax_.emplace(m_.static_tolerance);
    if (m_.tip_growth.enabled) grower_.emplace(m_);
    for (const auto& mat : m_.materials) breakable_ = breakable_ || std::isfinite(mat.law.eps_cut);
    breakable_ = breakable_ || m_.precrack_pairs > 0 || m_.tip_growth.enabled;
    least_ = std::max<std::size_t>(2, std::size_t(m_.fragment_fraction * double(m_.points.x0.size())));
    pieces0_ = pieces(m_.pairs, m_.points.x0.size(), least_);
  }

  const char* name() const override { return "pem"; }
  const RunSettings& settings() const override { return m_; }
  std::pair<double, std::string> work_per_step() const override { return {double(m_.pair_count), "pair"}; }

  std::vector<std::string> describe() const override {
    const auto& m = m_;
    std::vector<std::string> out = {
        format("%s%dD %s, pem: %zu particles (mesh nodes, %s) in %zu regions, %zu elements, %zu pairs (%zu cut by "
               "pre-cracks)",
               m.title.empty() ? "" : (m.title + ": ").c_str(), Dim, analysis_name(m.analysis), m.points.x0.size(),
               m.mesh_source.c_str(), m.regions.size(), m.mesh.element_count(), m.pair_count, m.precrack_pairs),
        format("mesh: mean pair length %.6g m; friction %.3g on closed broken pairs", m.mesh_size, m.friction)};
    for (const auto& mat : m.materials) {
      const auto& l = mat.law;
      std::string breaks = m.tip_growth.enabled      ? "pairs are cut only where a tip grows (pem.tip_growth)"
                           : !std::isfinite(l.eps_cut) ? "pairs never break"
                           : l.plastic()              ? format("yield stretch %.4g, cutoff stretch %.4g", l.eps_yield, l.eps_cut)
                           : l.eps_cut > l.eps_peak  ? format("peak stretch %.4g, cutoff stretch %.4g", l.eps_peak, l.eps_cut)
                                                     : format("brittle, cutoff stretch %.4g", l.eps_cut);
      out.push_back(format("%s (%s): network E = %.6g Pa, nu = %.4g, anisotropy %.2f %%; %s", mat.name.c_str(),
                           mat.type.c_str(), mat.E_network, mat.nu_network, 100 * mat.anisotropy, breaks.c_str()));
    }
    out.push_back(format("dt = %.6g s (stable limit sqrt(2 m / sum k): %.6g s), %ld steps to %.6g s; a step breaking more "
                         "than %.3g of the pairs is halved (up to %d times)",
                         m.dt, m.stable_dt, static_cast<long>(std::ceil(m.end_time / m.dt - 1e-9)), m.end_time,
                         m.break_limit, m.max_halvings));
    if (m.tip_growth.enabled) {
      const auto& g = m.tip_growth;
      out.push_back(format("tip growth: %zu tips; pairs do not break on their own; K_I, K_II from the faces' jumps "
                           "fitted out to %.6g m behind a tip; where K_eq reaches K_Ic a tip advances %.6g m at the "
                           "maximum hoop stress angle, at most %.6g m/s",
                           m.tips.size(), g.radius, g.length, g.max_speed));
      for (const auto& t : m.tips)
        out.push_back(format("  tip of '%s' at %s: K_Ic %.6g Pa sqrt(m) ('%s')", t.crack.c_str(),
                             position_text<Dim>(t.start).c_str(), t.toughness, t.material.c_str()));
    }
    if (m.equilibrium.enabled)
      out.push_back(format("equilibrium: ends when the largest speed < %.3g m/s and the relative residual < %.3g for "
                           "%d checks in a row (every %d steps)",
                           m.equilibrium.velocity, m.equilibrium.residual, m.equilibrium.checks, m.equilibrium.interval));
    if (m.stop_on_separation && breakable_)
      out.push_back(format("ends if the body separates (a new piece of at least %zu particles)", least_));
    out.push_back(format("output: every %.6g s (%zu fields%s), global.csv every %.6g s", m.output.interval,
                         m.output.fields.size(), breakable_ ? ", crack paths" : "", m.output.global_interval));
    describe_static(m, out);
    return out;
  }

  StepProblem step() override {
    solver_.step();
    const long s = solver_.step_count();
    if (grower_) grower_->check(solver_.time());
    if (relax_ && relax_->due(s)) {
      const auto g = solver_.global_state();
      m_.damping = relax_->check(g.time, g.strain, g.kinetic, m_.points);
    }
    if (m_.equilibrium.enabled && s % m_.equilibrium.interval == 0) {
      const auto g = solver_.balance();
      last_speed_ = g.max_speed, last_residual_ = g.relative_residual;
      if (g.max_speed < m_.equilibrium.velocity && g.relative_residual < m_.equilibrium.residual) {
        if (++calm_ >= m_.equilibrium.checks && end_ == End::None) end_ = End::Equilibrium, end_time_ = solver_.time();
      } else {
        calm_ = 0;
      }
    }
    if (m_.stop_on_separation && breakable_ && s % 100 == 0) {
      const std::size_t now = pieces(m_.pairs, m_.points.x0.size(), least_);
      if (now > pieces0_ && end_ == End::None) end_ = End::Separated, end_time_ = solver_.time();
    }
    return {};
  }
  bool static_reached() const override { return end_ != End::None || (relax_ && relax_->reached()); }
  std::string relaxation_state() const override {
    if (end_ == End::Equilibrium)
      return format("equilibrium: largest speed %.3g m/s, relative residual %.3g, for %d checks", last_speed_,
                    last_residual_, calm_);
    if (end_ == End::Separated) return "the body separated into pieces (pairs broken through)";
    if (relax_) return relax_->state();
    if (m_.equilibrium.enabled)
      return format("largest speed %.3g m/s, relative residual %.3g", last_speed_, last_residual_);
    return {};
  }
  double time() const override { return solver_.time(); }
  long step_count() const override { return solver_.step_count(); }
  std::string fastest_point() const override {
    const auto& P = m_.points;
    const std::size_t f = fastest<Dim>(P.v);
    std::ostringstream s;
    s << "particle " << f << " at " << position_text<Dim>(P.x0[f] + P.u[f]) << ", speed " << P.v[f].norm() << " m/s";
    return s.str();
  }

  std::vector<std::string> global_columns() const override {
    std::vector<std::string> c = {"time_s", "step", "kinetic_energy_J", "strain_energy_J", "external_work_J",
                                  "damping_loss_J", "total_energy_J", "broken_pairs", "residual_force_N",
                                  "relative_residual", "max_speed_m_per_s", "momentum_x_kg_m_per_s",
                                  "momentum_y_kg_m_per_s"};
    if (Dim == 3) c.push_back("momentum_z_kg_m_per_s");
    return c;
  }
  GlobalRow global_row() const override {
    const auto g = solver_.global_state();
    GlobalRow r;
    r.values = {g.time, double(g.step), g.kinetic, g.strain, g.external_work, g.damping_loss, g.total(),
                double(g.broken), g.residual, g.relative_residual, g.max_speed};
    for (int d = 0; d < Dim; ++d) r.values.push_back(g.momentum[d]);
    r.total_energy = g.total();
    r.external_work = g.external_work;
    return r;
  }

  std::vector<std::string> frame_series() const override {
    if (breakable_) return {"particles", "cracks"};
    return {"particles"};
  }
  io::PointSet frame(std::size_t series) override {
    if (series == 1) return tracer_.trace(solver_.positions(), m_.pairs);
    return particles();
  }

  nlohmann::json run_info() const override {
    nlohmann::json j;
    // "end": why the run ended before time.end (null: it did not); "ended_at": when.
    if (end_ == End::None) j["end"] = nullptr;
    else j["end"] = end_ == End::Equilibrium ? "equilibrium" : "separated";
    j["ended_at_s"] = end_ == End::None ? nlohmann::json(nullptr) : nlohmann::json(end_time_);
    j["halved_steps"] = solver_.halved_steps();
    nlohmann::json mats = nlohmann::json::array();
    for (const auto& mat : m_.materials)
      mats.push_back({{"name", mat.name}, {"E_Pa", mat.E_network}, {"nu", mat.nu_network},
                      {"anisotropy", mat.anisotropy},
                      {"peak_stretch", std::isfinite(mat.law.eps_peak) ? nlohmann::json(mat.law.eps_peak) : nlohmann::json(nullptr)},
                      {"cutoff_stretch", std::isfinite(mat.law.eps_cut) ? nlohmann::json(mat.law.eps_cut) : nlohmann::json(nullptr)}});
    j["pair_network"] = mats;
    // Pairs and those broken during the run, by the material whose law they follow (the weakest of
    // their elements): where cracks ran, e.g. the interface phase of a concrete.
    std::vector<std::size_t> all(m_.materials.size(), 0), broke(m_.materials.size(), 0);
    const auto& N = m_.pairs;
    for (std::size_t i = 0; i < m_.points.x0.size(); ++i)
      for (int64_t e = N.offset[i]; e < N.offset[i + 1]; ++e)
        if (static_cast<std::size_t>(N.partner[e]) > i) {
          ++all[N.law[e]];
          if (N.initial[e] && !N.intact[e]) ++broke[N.law[e]];
        }
    for (std::size_t k = 0; k < m_.materials.size(); ++k) {
      j["pairs_by_material"][m_.materials[k].name] = all[k];
      j["broken_pairs_by_material"][m_.materials[k].name] = broke[k];
    }
    if (grower_) j["tips"] = grower_->info();
    if (relax_)
      j["static"] = {{"tolerance", relax_->tolerance()}, {"reached", relax_->reached()},
                     {"lowest_mode_rad_per_s", relax_->omega()}, {"damping_per_s", relax_->kappa()}};
    return j;
  }

  void save(StateWriter& w) const override {
    solver_.save(w);
    w.value(end_), w.value(end_time_), w.value(calm_), w.value(last_speed_), w.value(last_residual_);
    if (relax_) relax_->save(w);
    if (grower_) grower_->save(w);
  }
  void load(StateReader& r) override {
    solver_.load(r);
    r.value(end_), r.value(end_time_), r.value(calm_), r.value(last_speed_), r.value(last_residual_);
    if (relax_) relax_->load(r), m_.damping = relax_->kappa();
    if (grower_) grower_->load(r);
  }

 private:
  enum class End : int32_t { None, Equilibrium, Separated };

  io::PointSet particles() const {
    const auto& P = m_.points;
    const auto y = solver_.positions();
    io::PointSetBuilder<Dim> b(m_.output.fields, P.x0.size(), [&](std::size_t p) { return y[p]; });
    std::vector<Sym<Dim>> sig;
    if (b.wants_stress()) sig = solver_.stress();
    std::vector<double> phi;
    if (b.wants("damage")) phi = solver_.damage();
    b.add_vectors("displacement", P.u);
    b.add_vectors("velocity", P.v);
    b.add_scalars("damage", [&](std::size_t p) { return phi[p]; });
    b.add_scalars("material", [&](std::size_t p) { return double(P.material[p]); });
    b.add_scalars("volume", [&](std::size_t p) { return P.volume[p]; });
    b.add_scalars("size", [&](std::size_t p) { return P.size[p]; });
    b.add_stress([&](std::size_t p) { return sig[p]; });
    return b.take();
  }

  PemSystem<Dim> m_;
  PemSolver<Dim> solver_;
  CrackTracer<Dim> tracer_;
  std::optional<Relaxation> relax_;
  std::optional<TipGrower<Dim>> grower_;
  bool breakable_ = false;
  std::size_t least_ = 2, pieces0_ = 0;
  End end_ = End::None;
  double end_time_ = -1, last_speed_ = 0, last_residual_ = 0;
  int32_t calm_ = 0;
};

}  // namespace
}  // namespace cleave::pem

CLEAVE_REGISTER_METHOD("pem", cleave::pem::PemMethod)
