#include "libmpm/method/run_loop.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/io/csv_writer.hpp"
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

// checkpoint.bin: this header, the loop's counters, then the method's state (Method::save).
// Format 4 is the first shared by every method (formats 1-3 were per method); 5 adds the crack-tip
// table's last records (method/tip_table.hpp) to every method's state.
constexpr char kMagic[8] = {'C', 'L', 'V', 'E', 'C', 'K', 'P', '5'};

struct LoopCounters {
  uint64_t scene_hash = 0;
  int64_t next_frame = 0;  // index of the next frame of every series (64 bits: no padding in the file)
  double next_frame_time = 0.0, next_global_time = 0.0, next_tip_time = 0.0;
};

template <int Dim>
void write_checkpoint(const fs::path& file, const Method<Dim>& method, const LoopCounters& c) {
  const auto tmp = file.string() + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error(tmp + ": cannot write checkpoint");
    o.write(kMagic, sizeof kMagic);
    char name[24] = {};
    std::strncpy(name, method.name(), sizeof name - 1);
    o.write(name, sizeof name);
    StateWriter w(o);
    w.value(uint32_t(Dim));
    w.value(c);
    method.save(w);
    if (!o) throw std::runtime_error(tmp + ": error while writing checkpoint");
  }
  fs::rename(tmp, file);
}

template <int Dim>
LoopCounters read_checkpoint(const fs::path& file, Method<Dim>& method, uint64_t scene_hash) {
  std::ifstream i(file, std::ios::binary);
  if (!i) throw std::runtime_error(file.string() + ": no checkpoint to resume from");
  char magic[8] = {}, name[24] = {};
  i.read(magic, sizeof magic);
  if (!i || std::memcmp(magic, kMagic, 7) != 0) throw std::runtime_error(file.string() + ": not a Cleave checkpoint");
  if (magic[7] != kMagic[7])
    throw std::runtime_error(file.string() + ": written by an earlier Cleave (checkpoint format " +
                             std::string(1, magic[7]) + "; this version reads format " +
                             std::string(1, kMagic[7]) + "); run without --resume");
  i.read(name, sizeof name);
  name[sizeof name - 1] = 0;
  StateReader r(i, file.string());
  uint32_t dim = 0;
  r.value(dim);
  if (std::string(name) != method.name() || dim != uint32_t(Dim))
    throw std::runtime_error(file.string() + ": the checkpoint is of a " + std::to_string(dim) + "D " + name +
                             " run; the scene is a " + std::to_string(Dim) + "D " + method.name() +
                             " scene (run without --resume)");
  LoopCounters c;
  r.value(c);
  if (c.scene_hash != scene_hash)
    throw std::runtime_error(file.string() + ": written for a different scene; run without --resume");
  method.load(r);
  return c;
}

}  // namespace

template <int Dim>
RunSummary run_method(Method<Dim>& method, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const RunSettings& set = method.settings();
  const fs::path out = opt.out;
  const fs::path ck_path = out / "checkpoint.bin", csv_path = out / "global.csv", tips_path = out / "crack_tips.csv";
  if (opt.resume && !fs::exists(ck_path)) throw std::runtime_error(ck_path.string() + ": no checkpoint to resume from");
  fs::create_directories(out);

  const std::vector<std::string> series = method.frame_series();
  std::vector<io::PvdIndex> pvd;
  for (const auto& s : series) pvd.emplace_back(out / (s + ".pvd"));
  const std::vector<std::string> tip_cols = method.tip_columns();
  const bool tips = !tip_cols.empty();

  LoopCounters ck;
  if (opt.resume) {
    ck = read_checkpoint<Dim>(ck_path, method, opt.scene_hash);
    for (std::size_t k = 0; k < series.size(); ++k) pvd[k] = io::resumed_series(out / (series[k] + ".pvd"), method.time());
    io::CsvSeries::truncate_after(csv_path, method.time());
    io::CsvSeries::truncate_after(tips_path, method.time());
  } else {
    // A fresh run replaces the outputs of an earlier one in the same directory (of any method).
    io::remove_run_outputs(out, {"particles", "cracks"}, {"global.csv", "checkpoint.bin", "run.json", "crack_tips.csv"});
  }
  io::CsvSeries csv(csv_path, method.global_columns(), opt.resume);
  std::optional<io::CsvSeries> tip_csv;
  if (tips) tip_csv.emplace(tips_path, tip_cols, opt.resume);
  auto status = [&](const char* s, const std::string& msg) {
    nlohmann::json info = method.run_info();
    info["method"] = method.name();
    io::write_run_status(out, s, msg, method.step_count(), method.time(), info);
  };
  status("running", "");

  const double eps = 1e-9 * set.dt;
  RunSummary sum;
  auto write_frame = [&]() {
    for (std::size_t k = 0; k < series.size(); ++k) {
      const std::string name = io::frame_file_name(series[k], static_cast<int>(ck.next_frame));
      io::write_vtu(out / name, method.frame(k));
      pvd[k].add(method.time(), name);
      pvd[k].write();
    }
    ++ck.next_frame;
    ++sum.frames;
  };
  auto checkpoint = [&]() {
    ck.scene_hash = opt.scene_hash;
    write_checkpoint<Dim>(ck_path, method, ck);
    status("running", "");  // run.json follows the run: step and time of the last checkpoint
  };
  auto record_global = [&]() {
    const GlobalRow g = method.global_row();
    csv.row(g.values);
    sum.observe_energy(g.total_energy);
    return g;
  };
  auto record_tips = [&]() {
    for (const auto& row : method.tip_rows()) tip_csv->row(row);
  };
  auto abort_run = [&](const std::string& msg) {
    write_frame();
    status("aborted", msg);
    throw RunAborted(msg);
  };
  auto at = [&](double t) {
    std::ostringstream s;
    s << "step " << method.step_count() << ", time " << t << " s: ";
    return s.str();
  };

  if (!opt.resume) {
    record_global();
    if (tips) record_tips();
    write_frame();
    ck.next_frame_time = set.output.interval;
    ck.next_global_time = set.output.global_interval;
    ck.next_tip_time = set.output.tip_interval;
    checkpoint();
  }

  // ETA from the progress since this process started.
  const double t_start = method.time();
  auto last_report = clock::now();
  while (method.time() < set.end_time - eps) {
    const StepProblem problem = method.step();
    const double t = method.time();
    const bool last = t >= set.end_time - eps;
    if (opt.log)
      if (const std::string w = method.take_warning(); !w.empty()) opt.log(w);
    // The checks: the energy's at every global.csv row, and at a step with a problem too; every
    // one that trips is reported, the energy's first, then the step's problem.
    const bool global_due = t >= ck.next_global_time - eps || last;
    if (problem || global_due) {
      const GlobalRow g = record_global();
      if (global_due) ck.next_global_time += set.output.global_interval;
      std::vector<std::string> tripped;
      const double ref = std::max({sum.first_energy, std::fabs(g.external_work), 1e-300});
      if (!std::isfinite(g.total_energy)) {
        tripped.push_back("energy is not finite");
      } else if (g.total_energy > set.energy_blowup_factor * ref && g.total_energy > 1e-12) {
        std::ostringstream msg;
        // Name the fastest point: where the blow-up is.
        msg << "energy blow-up, total energy " << g.total_energy << " J exceeds " << set.energy_blowup_factor
            << " x the reference " << ref << " J; fastest " << method.fastest_point();
        tripped.push_back(msg.str());
      }
      if (problem) tripped.push_back(problem.what);
      if (!tripped.empty()) {
        std::string msg = at(t) + tripped[0];
        for (std::size_t k = 1; k < tripped.size(); ++k) msg += "; also " + tripped[k];
        abort_run(msg);
      }
    }
    if (tips && (t >= ck.next_tip_time - eps || last)) {
      record_tips();
      while (ck.next_tip_time <= t + eps) ck.next_tip_time += set.output.tip_interval;
    }
    if (t >= ck.next_frame_time - eps || last) {
      write_frame();
      ck.next_frame_time += set.output.interval;
      checkpoint();
    }
    if (opt.progress && std::chrono::duration<double>(clock::now() - last_report).count() >= opt.progress_interval_s) {
      last_report = clock::now();
      RunProgress p;
      p.step = method.step_count();
      p.time = t;
      p.end_time = set.end_time;
      p.wall_s = std::chrono::duration<double>(last_report - t0).count();
      const double frac = (t - t_start) / std::max(set.end_time - t_start, 1e-300);
      p.eta_s = frac > 0 ? p.wall_s * (1.0 - frac) / frac : 0.0;
      opt.progress(p);
    }
  }
  sum.steps = method.step_count();
  sum.time = method.time();
  sum.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
  status("complete", "");
  return sum;
}

template RunSummary run_method<2>(Method<2>&, const RunOptions&);
template RunSummary run_method<3>(Method<3>&, const RunOptions&);

}  // namespace cleave
