#include "libmpm/solver/run.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "libmpm/core/error.hpp"
#include "libmpm/io/checkpoint.hpp"
#include "libmpm/io/crack_output.hpp"
#include "libmpm/io/csv_writer.hpp"
#include "libmpm/io/particle_fields.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/run_files.hpp"
#include "libmpm/io/vtu_writer.hpp"

namespace cleave {
namespace fs = std::filesystem;

uint64_t scene_hash(const nlohmann::json& scene) {
  // FNV-1a of the canonical dump: stable across runs and builds.
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : scene.dump()) h = (h ^ c) * 1099511628211ull;
  return h;
}

namespace {

template <int Dim>
std::vector<std::string> global_columns() {
  std::vector<std::string> c = {"time", "step", "kinetic_energy", "strain_energy", "external_work", "total_energy",
                                "momentum_x", "momentum_y"};
  if (Dim == 3) c.push_back("momentum_z");
  return c;
}

template <int Dim>
std::vector<double> global_row(const GlobalState<Dim>& g) {
  std::vector<double> r = {g.time, double(g.step), g.kinetic, g.strain, g.external_work, g.total()};
  for (int d = 0; d < Dim; ++d) r.push_back(g.momentum[d]);
  return r;
}

}  // namespace

template <int Dim>
RunSummary run_model(Model<Dim>& m, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const fs::path out = opt.out;
  if (opt.resume && !fs::exists(out / "checkpoint.bin"))
    throw std::runtime_error((out / "checkpoint.bin").string() + ": no checkpoint to resume from");
  fs::create_directories(out);
  auto stepper = make_stepper<Dim>(m);

  io::CheckpointInfo ck;
  io::PvdIndex pvd(out / "particles.pvd");
  const bool cracks = !m.cracks.empty();
  io::PvdIndex crack_pvd(out / "cracks.pvd");
  const fs::path csv_path = out / "global.csv";
  const fs::path tips_path = out / "crack_tips.csv";
  const bool tips = cracks && m.crack_tips.has_value();
  const fs::path ck_path = out / "checkpoint.bin";
  if (opt.resume) {
    ck = io::read_checkpoint<Dim>(ck_path, m);
    if (ck.scene_hash != opt.scene_hash)
      throw std::runtime_error(ck_path.string() + ": written for a different scene; run without --resume");
    stepper->restore(ck.time, ck.step, ck.external_work);
    pvd = io::resumed_series(out / "particles.pvd", ck.time);
    if (cracks) crack_pvd = io::resumed_series(out / "cracks.pvd", ck.time);
    io::CsvSeries::truncate_after(csv_path, ck.time);
    io::CsvSeries::truncate_after(tips_path, ck.time);
  } else {
    // A fresh run replaces the outputs of an earlier one in the same directory.
    io::remove_run_outputs(out, {"particles", "cracks"}, {"global.csv", "checkpoint.bin", "run.json", "crack_tips.csv"});
  }
  io::CsvSeries csv(csv_path, global_columns<Dim>(), opt.resume);
  // crack_tips.csv: rows every crack_tips.interval (k * interval, so a resumed run finds its next
  // row time from the checkpoint time alone).
  std::optional<io::CsvSeries> tip_csv;
  double next_tip_time = 0.0;
  if (tips) {
    tip_csv.emplace(tips_path, std::vector<std::string>{"time", "crack", "tip", "x", "y", "J1", "J2", "KI", "KII"},
                    opt.resume);
    const double iv = m.crack_tips->interval;
    next_tip_time = opt.resume ? (std::floor(ck.time / iv + 1e-9) + 1.0) * iv : 0.0;
  }
  io::write_run_status(out, "running", "", stepper->step_count(), stepper->time());

  const double dt = m.dt;
  const double eps = 1e-9 * dt;
  RunSummary sum;
  auto write_frame = [&]() {
    const std::string name = io::frame_file_name("particles", ck.next_frame);
    io::write_vtu(out / name, io::particle_point_set<Dim>(m, m.output.fields));
    pvd.add(stepper->time(), name);
    pvd.write();
    if (cracks) {
      const std::string cname = io::frame_file_name("cracks", ck.next_frame);
      io::write_vtu(out / cname, tips ? io::crack_point_set(m.cracks, stepper->crack_tip_parameters(*m.crack_tips))
                                      : io::crack_point_set(m.cracks));
      crack_pvd.add(stepper->time(), cname);
      crack_pvd.write();
    }
    ++ck.next_frame;
    ++sum.frames;
  };
  auto checkpoint = [&]() {
    ck.scene_hash = opt.scene_hash;
    ck.time = stepper->time();
    ck.step = stepper->step_count();
    ck.external_work = stepper->external_work();
    io::write_checkpoint<Dim>(ck_path, m, ck);
  };
  auto record_global = [&]() {
    const auto g = stepper->global_state();
    csv.row(global_row<Dim>(g));
    sum.observe_energy(g.total());
    return g;
  };
  auto record_tips = [&]() {
    for (const auto& r : stepper->crack_tip_parameters(*m.crack_tips))
      tip_csv->row({stepper->time(), double(r.crack), double(r.end), r.x.x(), r.x.y(), r.J1, r.J2, r.KI, r.KII});
  };
  auto abort_run = [&](const std::string& msg) {
    write_frame();
    io::write_run_status(out, "aborted", msg, stepper->step_count(), stepper->time());
    throw RunAborted(msg);
  };

  if (!opt.resume) {
    record_global();
    if (tips) {
      record_tips();
      next_tip_time = m.crack_tips->interval;
    }
    write_frame();
    ck.next_frame_time = m.output.interval;
    ck.next_global_time = m.output.global_interval;
    checkpoint();
  }

  // ETA from the progress since this process started (ck.time moves on at every checkpoint).
  const double t_start = stepper->time();
  auto last_report = clock::now();
  while (stepper->time() < m.end_time - eps) {
    const StepProblem problem = stepper->step();
    const double t = stepper->time();
    if (opt.log)
      if (const std::string w = stepper->take_warning(); !w.empty()) opt.log(w);
    if (problem) {
      const auto& x = m.particles.x[problem.particle];
      std::ostringstream msg;
      msg << "step " << stepper->step_count() << ", time " << t << " s: particle " << problem.particle << " at (";
      for (int d = 0; d < Dim; ++d) msg << (d ? ", " : "") << x[d];
      msg << ") m " << problem.what;
      record_global();
      abort_run(msg.str());
    }
    if (t >= ck.next_global_time - eps || t >= m.end_time - eps) {
      const auto g = record_global();
      ck.next_global_time += m.output.global_interval;
      if (!std::isfinite(g.total())) abort_run("step " + std::to_string(g.step) + ", time " + std::to_string(t) +
                                               " s: energy is not finite");
      const double ref = std::max({sum.first_energy, std::fabs(g.external_work), 1e-300});
      if (g.total() > m.energy_blowup_factor * ref && g.total() > 1e-12) {
        std::ostringstream msg;
        // Name the fastest particle: where the blow-up is.
        std::size_t fast = 0;
        for (std::size_t p = 1; p < m.particles.size(); ++p)
          if (m.particles.v[p].squaredNorm() > m.particles.v[fast].squaredNorm()) fast = p;
        msg << "step " << g.step << ", time " << t << " s: energy blow-up, total energy " << g.total()
            << " J exceeds " << m.energy_blowup_factor << " x the reference " << ref << " J; fastest particle "
            << fast << " at (";
        for (int d = 0; d < Dim; ++d) msg << (d ? ", " : "") << m.particles.x[fast][d];
        msg << ") m, speed " << m.particles.v[fast].norm() << " m/s";
        abort_run(msg.str());
      }
    }
    if (tips && (t >= next_tip_time - eps || t >= m.end_time - eps)) {
      record_tips();
      while (next_tip_time <= t + eps) next_tip_time += m.crack_tips->interval;
    }
    if (t >= ck.next_frame_time - eps || t >= m.end_time - eps) {
      write_frame();
      ck.next_frame_time += m.output.interval;
      checkpoint();
    }
    if (opt.progress && std::chrono::duration<double>(clock::now() - last_report).count() >= opt.progress_interval_s) {
      last_report = clock::now();
      RunProgress p;
      p.step = stepper->step_count();
      p.time = t;
      p.end_time = m.end_time;
      p.wall_s = std::chrono::duration<double>(last_report - t0).count();
      const double frac = (t - t_start) / std::max(m.end_time - t_start, 1e-300);
      p.eta_s = frac > 0 ? p.wall_s * (1.0 - frac) / frac : 0.0;
      opt.progress(p);
    }
  }
  sum.steps = stepper->step_count();
  sum.time = stepper->time();
  sum.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
  io::write_run_status(out, "complete", "", sum.steps, sum.time);
  return sum;
}

template RunSummary run_model<2>(Model<2>&, const RunOptions&);
template RunSummary run_model<3>(Model<3>&, const RunOptions&);

}  // namespace cleave
