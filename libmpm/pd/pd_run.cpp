#include "libmpm/pd/pd_run.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "libmpm/core/error.hpp"
#include "libmpm/io/csv_writer.hpp"
#include "libmpm/io/particle_fields.hpp"
#include "libmpm/io/point_set.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/run_files.hpp"
#include "libmpm/io/vtu_writer.hpp"
#include "libmpm/pd/pd_solver.hpp"
#include "libmpm/pd/tips.hpp"

namespace cleave::pd {
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kMagic = 0x31504B4344504C43ull;  // "CLPDCKP1"

// Counters saved beside the point state so a stopped run resumes from its last frame.
template <int Dim>
struct PdCheckpoint {
  uint64_t scene_hash = 0;
  double time = 0.0;
  long step = 0;
  double external_work = 0.0, damping_loss = 0.0;
  int next_frame = 0;
  double next_frame_time = 0.0, next_global_time = 0.0, next_tip_time = 0.0;
  double branch_time = -1.0, branch_x = 0.0, branch_y = 0.0;
};

template <class T>
void put(std::ofstream& o, const std::vector<T>& v) {
  o.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
void get(std::ifstream& i, std::vector<T>& v, const fs::path& f) {
  i.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  if (!i) throw std::runtime_error(f.string() + ": checkpoint is truncated");
}

template <int Dim>
void write_checkpoint(const fs::path& file, const PdSystem<Dim>& m, const PdCheckpoint<Dim>& c,
                      const std::vector<Vec<Dim>>& last_tip, const std::vector<double>& last_tip_time) {
  const auto tmp = file.string() + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error(tmp + ": cannot write checkpoint");
    const uint64_t header[4] = {kMagic, uint64_t(Dim), uint64_t(m.points.size()), uint64_t(m.nb.size())};
    o.write(reinterpret_cast<const char*>(header), sizeof(header));
    o.write(reinterpret_cast<const char*>(&c), sizeof(c));
    put(o, m.points.u), put(o, m.points.v), put(o, m.points.a), put(o, m.nb.intact);
    put(o, last_tip), put(o, last_tip_time);
    if (!o) throw std::runtime_error(tmp + ": error while writing checkpoint");
  }
  fs::rename(tmp, file);
}

template <int Dim>
PdCheckpoint<Dim> read_checkpoint(const fs::path& file, PdSystem<Dim>& m, std::vector<Vec<Dim>>& last_tip,
                                  std::vector<double>& last_tip_time) {
  std::ifstream i(file, std::ios::binary);
  if (!i) throw std::runtime_error(file.string() + ": no checkpoint to resume from");
  uint64_t header[4];
  PdCheckpoint<Dim> c;
  i.read(reinterpret_cast<char*>(header), sizeof(header));
  i.read(reinterpret_cast<char*>(&c), sizeof(c));
  if (!i || header[0] != kMagic) throw std::runtime_error(file.string() + ": not a Cleave peridynamics checkpoint");
  if (header[1] != uint64_t(Dim) || header[2] != m.points.size() || header[3] != m.nb.size())
    throw std::runtime_error(file.string() + ": checkpoint holds another lattice (" + std::to_string(header[2]) +
                             " points in " + std::to_string(header[1]) + "D); the scene builds " +
                             std::to_string(m.points.size()) + " in " + std::to_string(Dim) + "D");
  get(i, m.points.u, file), get(i, m.points.v, file), get(i, m.points.a, file), get(i, m.nb.intact, file);
  get(i, last_tip, file), get(i, last_tip_time, file);
  return c;
}

}  // namespace

template <int Dim>
io::PointSet pd_point_set(const PdSystem<Dim>& m, const PdSolver<Dim>& s) {
  const auto& P = m.points;
  const auto& fields = m.output.fields;
  const std::size_t n = P.size();
  io::PointSet ps;
  ps.points.assign(3 * n, 0.0);
  // Current positions, as for MPM particles (the renderer draws the deformed body).
  for (std::size_t p = 0; p < n; ++p)
    for (int d = 0; d < Dim; ++d) ps.points[3 * p + d] = P.x0[p][d] + P.u[p][d];
  auto add = [&](const char* name, int comps, auto&& fill) {
    if (!fields.count(name)) return;
    io::PointArray a{name, comps, std::vector<double>(comps * n, 0.0)};
    for (std::size_t p = 0; p < n; ++p) fill(p, &a.values[comps * p]);
    ps.arrays.push_back(std::move(a));
  };
  std::vector<Sym<Dim>> sig;
  if (fields.count("stress") || fields.count("von_mises") || fields.count("principal_stress_difference"))
    sig = s.stress();
  std::vector<double> phi;
  if (fields.count("damage")) phi = s.damage();
  auto vtk6 = [](const Sym<Dim>& t, double* o) {
    for (int k = 0; k < kSymComponents<Dim>; ++k) o[k] = t[k];  // 2D: xx yy zz xy, then 0 0
  };
  add("displacement", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.u[p][d]; });
  add("velocity", 3, [&](std::size_t p, double* o) { for (int d = 0; d < Dim; ++d) o[d] = P.v[p][d]; });
  add("damage", 1, [&](std::size_t p, double* o) { o[0] = phi[p]; });
  add("stress", 6, [&](std::size_t p, double* o) { vtk6(sig[p], o); });
  add("material", 1, [&](std::size_t p, double* o) { o[0] = P.material[p]; });
  add("volume", 1, [&](std::size_t p, double* o) { o[0] = P.volume[p]; });
  add("size", 1, [&](std::size_t p, double* o) { o[0] = m.dx; });  // each point's lattice cell
  add("von_mises", 1, [&](std::size_t p, double* o) { o[0] = io::von_mises<Dim>(sig[p]); });
  add("principal_stress_difference", 1,
      [&](std::size_t p, double* o) { o[0] = io::principal_stress_difference<Dim>(sig[p]); });
  return ps;
}

template <int Dim>
RunSummary run_pd(PdSystem<Dim>& m, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const fs::path out = opt.out;
  const fs::path ck_path = out / "checkpoint.bin", csv_path = out / "global.csv", tip_path = out / "crack_tips.csv";
  if (opt.resume && !fs::exists(ck_path))
    throw std::runtime_error(ck_path.string() + ": no checkpoint to resume from");
  fs::create_directories(out);

  const std::size_t nt = m.trackers.size();
  std::vector<Vec<Dim>> last_tip(nt, Vec<Dim>::Constant(std::nan("")));
  std::vector<double> last_tip_time(nt, -1.0);
  PdCheckpoint<Dim> ck;
  io::PvdIndex pvd(out / "particles.pvd");
  if (opt.resume) {
    ck = read_checkpoint<Dim>(ck_path, m, last_tip, last_tip_time);
    if (ck.scene_hash != opt.scene_hash)
      throw std::runtime_error(ck_path.string() + ": written for a different scene; run without --resume");
    pvd = io::resumed_series(out / "particles.pvd", ck.time);
    io::CsvSeries::truncate_after(csv_path, ck.time);
    io::CsvSeries::truncate_after(tip_path, ck.time);
  } else {
    io::remove_run_outputs(out, {"particles"}, {"global.csv", "checkpoint.bin", "run.json", "crack_tips.csv"});
  }
  // The solver computes the initial accelerations; on resume they are replaced by the saved ones
  // (bit-identical continuation) together with u, v and the bond states.
  std::vector<Vec<Dim>> u_saved, v_saved, a_saved;
  std::vector<uint8_t> intact_saved;
  if (opt.resume) u_saved = m.points.u, v_saved = m.points.v, a_saved = m.points.a, intact_saved = m.nb.intact;
  PdSolver<Dim> solver(m);
  if (opt.resume) {
    m.points.u = u_saved, m.points.v = v_saved, m.points.a = a_saved, m.nb.intact = intact_saved;
    solver.restore(ck.time, ck.step, ck.external_work, ck.damping_loss);
  }

  std::vector<std::string> cols = {"time", "step", "kinetic_energy", "strain_energy", "external_work",
                                   "damping_loss", "total_energy", "broken_bonds", "momentum_x", "momentum_y"};
  if (Dim == 3) cols.push_back("momentum_z");
  io::CsvSeries csv(csv_path, cols, opt.resume);
  std::vector<std::string> tcols = {"time", "branch", "x", "y"};
  if (Dim == 3) tcols.push_back("z");
  tcols.push_back("speed");
  io::CsvSeries tips(tip_path, tcols, opt.resume);

  auto extra = [&]() {
    nlohmann::json j;
    j["method"] = "peridynamics";
    nlohmann::json names = nlohmann::json::array();
    for (const auto& t : m.trackers) names.push_back(t.name);
    j["crack_tip_branches"] = names;  // crack_tips.csv "branch" = index into this list
    if (ck.branch_time >= 0) j["branching"] = {{"time", ck.branch_time}, {"x", ck.branch_x}, {"y", ck.branch_y}};
    else j["branching"] = nullptr;
    return j;
  };
  io::write_run_status(out, "running", "", solver.step_count(), solver.time(), extra());

  const double dt = m.dt, eps = 1e-9 * dt;
  RunSummary sum;
  auto write_frame = [&]() {
    const std::string name = io::frame_file_name("particles", ck.next_frame);
    io::write_vtu(out / name, pd_point_set<Dim>(m, solver));
    pvd.add(solver.time(), name);
    pvd.write();
    ++ck.next_frame;
    ++sum.frames;
  };
  auto checkpoint = [&]() {
    ck.scene_hash = opt.scene_hash;
    ck.time = solver.time();
    ck.step = solver.step_count();
    ck.external_work = solver.external_work();
    ck.damping_loss = solver.damping_loss();
    write_checkpoint<Dim>(ck_path, m, ck, last_tip, last_tip_time);
  };
  auto record_global = [&]() {
    const auto g = solver.global_state();
    std::vector<double> row = {g.time, double(g.step), g.kinetic, g.strain, g.external_work,
                               g.damping_loss, g.total(), double(g.broken)};
    for (int d = 0; d < Dim; ++d) row.push_back(g.momentum[d]);
    csv.row(row);
    sum.observe_energy(g.total());
    return g;
  };
  auto record_tips = [&]() {
    const auto phi = solver.damage();
    const double t = solver.time();
    for (std::size_t k = 0; k < nt; ++k) {
      const auto tip = find_tip<Dim>(m, phi, m.trackers[k], m.tip_threshold);
      if (!tip) continue;
      const Vec<Dim> x = m.points.x0[*tip];
      // Seed 003: v_i = |x_i - x_{i-1}| / (t_i - t_{i-1}) between successive tip records.
      const double speed = last_tip_time[k] >= 0 && t > last_tip_time[k]
                               ? (x - last_tip[k]).norm() / (t - last_tip_time[k]) : 0.0;
      std::vector<double> row = {t, double(k)};
      for (int d = 0; d < Dim; ++d) row.push_back(x[d]);
      row.push_back(speed);
      tips.row(row);
      last_tip[k] = x;
      last_tip_time[k] = t;
    }
    if constexpr (Dim == 2) {
      if (ck.branch_time < 0) {
        // Only columns ahead of the pre-cracks' damaged band at t = 0 can show a fork.
        if (auto b = find_branch(m, phi, -std::numeric_limits<double>::infinity(), m.tip_threshold)) {
          ck.branch_time = t, ck.branch_x = b->x, ck.branch_y = b->y;
          io::write_run_status(out, "running", "", solver.step_count(), t, extra());
        }
      }
    }
  };
  auto abort_run = [&](const std::string& msg) {
    write_frame();
    io::write_run_status(out, "aborted", msg, solver.step_count(), solver.time(), extra());
    throw RunAborted(msg);
  };

  if (!opt.resume) {
    record_global();
    record_tips();
    write_frame();
    ck.next_frame_time = m.output.interval;
    ck.next_global_time = m.output.global_interval;
    ck.next_tip_time = m.output.tip_interval;
    checkpoint();
  }
  // ETA from the progress since this process started (ck.time moves on at every checkpoint).
  const double t_start = solver.time();
  auto last_report = clock::now();
  while (solver.time() < m.end_time - eps) {
    solver.step();
    const double t = solver.time();
    const bool last = t >= m.end_time - eps;
    if (t >= ck.next_global_time - eps || last) {
      const auto g = record_global();
      ck.next_global_time += m.output.global_interval;
      if (!std::isfinite(g.total()))
        abort_run("step " + std::to_string(g.step) + ", time " + std::to_string(t) + " s: energy is not finite");
      const double ref = std::max({sum.first_energy, std::fabs(g.external_work), 1e-300});
      if (g.total() > m.energy_blowup_factor * ref && g.total() > 1e-12) {
        std::ostringstream msg;
        msg << "step " << g.step << ", time " << t << " s: energy blow-up, total energy " << g.total()
            << " J exceeds " << m.energy_blowup_factor << " x the reference " << ref << " J";
        abort_run(msg.str());
      }
    }
    if (t >= ck.next_tip_time - eps || last) {
      record_tips();
      ck.next_tip_time += m.output.tip_interval;
    }
    if (t >= ck.next_frame_time - eps || last) {
      write_frame();
      ck.next_frame_time += m.output.interval;
      checkpoint();
    }
    if (opt.progress && std::chrono::duration<double>(clock::now() - last_report).count() >= opt.progress_interval_s) {
      last_report = clock::now();
      RunProgress p;
      p.step = solver.step_count();
      p.time = t;
      p.end_time = m.end_time;
      p.wall_s = std::chrono::duration<double>(last_report - t0).count();
      const double frac = (t - t_start) / std::max(m.end_time - t_start, 1e-300);
      p.eta_s = frac > 0 ? p.wall_s * (1.0 - frac) / frac : 0.0;
      opt.progress(p);
    }
  }
  sum.steps = solver.step_count();
  sum.time = solver.time();
  sum.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
  io::write_run_status(out, "complete", "", sum.steps, sum.time, extra());
  return sum;
}

template RunSummary run_pd<2>(PdSystem<2>&, const RunOptions&);
template RunSummary run_pd<3>(PdSystem<3>&, const RunOptions&);
template io::PointSet pd_point_set<2>(const PdSystem<2>&, const PdSolver<2>&);
template io::PointSet pd_point_set<3>(const PdSystem<3>&, const PdSolver<3>&);

}  // namespace cleave::pd
