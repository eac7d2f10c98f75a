// cleave study: every run of a study as its own `cleave run` process (its own folder, its wall and
// CPU time and peak memory from wait4), a progress line across runs, a stop forwarded to the run in
// progress (which checkpoints), and a second invocation that skips the runs already done and resumes
// a stopped one. Then the measurements, errors and reports of study/.
#include "apps/cleave/study_cli.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "apps/cleave/progress.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/scene/scene.hpp"
#include "study/analysis.hpp"
#include "study/report.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace cleave::study;

namespace cleave::app {
namespace {

constexpr int kOk = 0, kBadInput = 2, kAborted = 3;

const char* kStudyHelp = R"(cleave study STUDY.json [--out DIR] [--threads N] [--check] [--quiet]

Runs every run of a study (docs/speed-accuracy.md) one after another, each as `cleave run` in its own
folder DIR/LABEL, measures the study's quantities, their errors against the references, and writes
  DIR/study.csv              one row per run: settings, status, steps, particles, wall and CPU time,
                             peak memory, each quantity and its error
  DIR/summary.md             the cheapest setting within each tolerance, observed orders, runs that
                             failed, stopped or missed their expectation
  DIR/work_precision.png     error against wall time (log-log), a line per series, points labelled by
                             cell size; DIR/convergence.png error against cell size with the order
                             (one pair per quantity: work_precision_NAME.png after the first)
Every run's scene is checked first (nothing runs when one is bad). A stopped study (Ctrl-C) stops
the run in progress at its current step; running the same command again skips the runs that ended
and resumes the stopped one.

Options:
  --out DIR     default: STUDY's name + "_study"
  --threads N   threads of each run (default: the study's "threads", else cleave run's default)
  --check       check the study and every run's scene, print the plan, run nothing
  --quiet       no progress line

Exit status: 0 every run completed (or met its expectation); 2 a bad study (the key named) or a run's
scene refused by cleave check; 3 a run failed or missed its expectation (the reports are written);
130/143 stopped.
)";

volatile std::sig_atomic_t g_stop = 0;
volatile pid_t g_child = 0;

void on_stop(int sig) {
  if (!g_stop) {
    g_stop = sig;
    if (g_child > 0) ::kill(g_child, sig);  // once: a second signal would kill the run at once
  }
}

struct ChildResult {
  int exit_code = -1;
  double wall_s = 0, cpu_s = 0, peak_mb = 0;
};

// Runs this program with `args` in its own process group (a terminal's Ctrl-C reaches the study,
// which passes it on once), stdout and stderr to files. `poll` runs about once a second.
ChildResult run_child(const std::vector<std::string>& args, const fs::path& out, const fs::path& err,
                      const std::function<void(double)>& poll) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot start a run: ") + std::strerror(errno));
  if (pid == 0) {
    ::setpgid(0, 0);
    ::signal(SIGINT, SIG_DFL), ::signal(SIGTERM, SIG_DFL);
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fo < 0 || fe < 0) ::_exit(126);
    ::dup2(fo, 1), ::dup2(fe, 2);
    std::vector<char*> argv;
    std::string self = "cleave";
    argv.push_back(self.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv("/proc/self/exe", argv.data());
    ::_exit(127);
  }
  g_child = pid;
  if (g_stop) ::kill(pid, g_stop);
  ChildResult r;
  int status = 0;
  struct rusage ru {};
  auto last_poll = t0;
  for (;;) {
    const pid_t w = ::wait4(pid, &status, WNOHANG, &ru);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("waiting for a run: ") + std::strerror(errno));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto now = std::chrono::steady_clock::now();
    if (poll && now - last_poll > std::chrono::seconds(1))
      last_poll = now, poll(std::chrono::duration<double>(now - t0).count());
  }
  g_child = 0;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu_s = ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec + 1e-6 * ru.ru_stime.tv_usec;
  r.peak_mb = ru.ru_maxrss / 1024.0;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

std::string read_text(const fs::path& f) {
  std::ifstream in(f);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The last "cleave: ..." line of a run's stderr (its reason), without the prefix.
std::string last_error(const std::string& err) {
  std::string best;
  std::size_t pos = 0;
  while ((pos = err.find("cleave: ", pos)) != std::string::npos) {
    const std::size_t end = err.find('\n', pos);
    const std::string line = err.substr(pos + 8, end == std::string::npos ? std::string::npos : end - pos - 8);
    if (line.rfind("warning", 0) != 0) best = line;
    pos = end == std::string::npos ? err.size() : end;
  }
  return best;
}

// "threads" is not a scene key: a study may vary it, and it becomes cleave run's --threads.
constexpr const char* kThreadsKey = "threads";

std::vector<std::string> set_args(const RunPlan& p) {
  std::vector<std::string> a;
  for (const auto& s : p.settings)
    if (s.key != kThreadsKey) a.push_back("--set"), a.push_back(s.key + "=" + s.value.dump());
  return a;
}

// The run's thread count: its "threads" setting, else the study's.
int run_threads(const RunPlan& p, int study_threads) {
  for (const auto& s : p.settings)
    if (s.key == kThreadsKey && s.value.is_number_integer() && s.value.get<int>() > 0) return s.value.get<int>();
  return study_threads;
}

json settings_json(const RunPlan& p) {
  json j = json::array();
  for (const auto& s : p.settings) j.push_back({s.key, s.value});
  return j;
}

struct Planned {
  long points = -1, steps = -1;
  double work() const { return points > 0 && steps > 0 ? double(points) * double(steps) : 1.0; }
};

// "estimate: 24960 points, 6450 steps, ..." of cleave check.
Planned parse_estimate(const std::string& check_out) {
  Planned p;
  std::smatch m;
  if (std::regex_search(check_out, m, std::regex("estimate: ([0-9]+) points, ([0-9]+) steps")))
    p.points = std::stol(m[1]), p.steps = std::stol(m[2]);
  return p;
}

// "table crack_tips.csv: time_s crack tip ..." lines of cleave check: file -> columns.
std::map<std::string, std::vector<std::string>> parse_tables(const std::string& check_out) {
  std::map<std::string, std::vector<std::string>> t;
  std::istringstream in(check_out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("table ", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::istringstream cols(line.substr(colon + 1));
    auto& v = t[line.substr(6, colon - 6)];
    for (std::string c; cols >> c;) v.push_back(c);
  }
  return t;
}

// A run's record from its folder and the study's own note of it (study_run.json).
void read_run_folder(RunRecord& r, const fs::path& dir) {
  const fs::path note = dir / "study_run.json";
  if (!fs::exists(note)) return;
  const json n = json::parse(read_text(note), nullptr, false);
  if (n.is_discarded()) return;
  r.exit_code = n.value("exit_code", -1);
  r.wall_s = n.value("wall_s", kNaN), r.cpu_s = n.value("cpu_s", kNaN), r.peak_mb = n.value("peak_memory_MB", kNaN);
  r.particles = n.value("particles", -1L);
  r.message = n.value("message", "");
  r.status = n.value("status", "failed");
  if (fs::exists(dir / "run.json")) {
    const json rj = json::parse(read_text(dir / "run.json"), nullptr, false);
    if (!rj.is_discarded()) {
      r.steps = rj.value("step", -1L);
      if (rj.contains("message") && rj["message"].is_string() && !rj["message"].get<std::string>().empty())
        r.message = rj["message"].get<std::string>();
    }
  }
}

bool tables_hold_nan(const fs::path& dir) {
  for (const char* f : {"global.csv", "crack_tips.csv", "crack_fronts.csv", "crack_growth.csv"}) {
    if (!fs::exists(dir / f)) continue;
    const Table t = read_table(dir / f);
    for (const auto& row : t.rows)
      for (std::size_t c = 0; c < row.size(); ++c)
        if (!std::isfinite(row[c])) return true;
  }
  return false;
}

int bad_study(const fs::path& file, const std::string& key, const std::string& reason) {
  std::fprintf(stderr, "cleave: %s: error at '%s': %s\n", file.string().c_str(), key.c_str(), reason.c_str());
  return kBadInput;
}

}  // namespace

int study_command(const std::vector<std::string>& args) {
  fs::path file, out;
  int threads = 0;
  bool check_only = false, quiet = false;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
      return args[++i];
    };
    try {
      if (a == "--help" || a == "-h") {
        std::fputs(kStudyHelp, stdout);
        return kOk;
      } else if (a == "--out") {
        out = value();
      } else if (a == "--threads") {
        const std::string v = value();
        threads = std::atoi(v.c_str());
        if (threads < 1 || std::to_string(threads) != v) throw std::invalid_argument("--threads needs a positive integer");
      } else if (a == "--check") {
        check_only = true;
      } else if (a == "--quiet") {
        quiet = true;
      } else if (!a.empty() && a[0] == '-') {
        throw std::invalid_argument("unknown option '" + a + "'");
      } else if (file.empty()) {
        file = a;
      } else {
        throw std::invalid_argument("unexpected argument '" + a + "'");
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cleave study: %s\n(see cleave study --help)\n", e.what());
      return kBadInput;
    }
  }
  if (file.empty()) {
    std::fprintf(stderr, "cleave study: needs a STUDY.json\n(see cleave study --help)\n");
    return kBadInput;
  }
  Study st;
  try {
    st = read_study(file);
  } catch (const StudyError& e) {
    return bad_study(file, e.key(), e.reason());
  }
  if (out.empty()) out = file.stem().string() + "_study";
  if (threads == 0) threads = st.threads;

  // Every run's scene, checked before anything runs: in this process (keys, values) and by cleave
  // check (what the method builds), whose estimate also gives the work for the ETA.
  std::vector<RunRecord> runs(st.runs.size());
  std::vector<Planned> planned(st.runs.size());
  fs::create_directories(out);
  for (std::size_t i = 0; i < st.runs.size(); ++i) {
    const RunPlan& p = st.runs[i];
    RunRecord& r = runs[i];
    r.plan = &p;
    // A run of the extremes suite may be meant to be refused: its refusal is its result.
    const bool may_be_refused = p.expect.has_value();
    try {
      r.scene = load_scene_file(p.scene);
      std::vector<std::string> kv;
      for (const auto& s : p.settings) {
        if (s.key != kThreadsKey) kv.push_back(s.key + "=" + s.value.dump());
        else if (!s.value.is_number_integer() || s.value.get<int>() < 1)
          return bad_study(file, "run '" + p.label + "'", "threads must be a positive integer (got " + s.value.dump() + ")");
      }
      apply_overrides(r.scene, kv);
    } catch (const SceneError& e) {
      if (!may_be_refused)
        return bad_study(file, "run '" + p.label + "'", p.scene.string() + ": error at '" + e.key_path() + "': " + e.reason());
    }
    const fs::path tmp_out = out / (".check_" + p.label + ".out"), tmp_err = out / (".check_" + p.label + ".err");
    std::vector<std::string> cargs{"check", p.scene.string()};
    for (const auto& s : set_args(p)) cargs.push_back(s);
    const ChildResult c = run_child(cargs, tmp_out, tmp_err, nullptr);
    const std::string cout_text = read_text(tmp_out), cerr_text = read_text(tmp_err);
    fs::remove(tmp_out), fs::remove(tmp_err);
    if (g_stop) return 128 + g_stop;
    if (c.exit_code != 0 && !may_be_refused) {
      // A key the study set is named as the study's; anything else as the scene's.
      const std::string why = last_error(cerr_text);
      std::smatch m;
      if (std::regex_search(why, m, std::regex("error at '([^']+)': (.*)$")))
        for (const auto& s : p.settings)
          if (m[1].str().rfind(s.key, 0) == 0) {
            std::fprintf(stderr, "cleave: %s: error at '%s' (set by the study, run '%s'): %s\n", file.string().c_str(),
                         m[1].str().c_str(), p.label.c_str(), m[2].str().c_str());
            return kBadInput;
          }
      return bad_study(file, "run '" + p.label + "' (" + settings_text(p.varied) + ")",
                       "cleave check refuses its scene: " + why);
    }
    if (c.exit_code != 0) {
      r.status = "refused", r.exit_code = c.exit_code, r.message = last_error(cerr_text);
      continue;
    }
    planned[i] = parse_estimate(cout_text);
    const auto tables = parse_tables(cout_text);
    for (std::size_t k = 0; k < st.quantities.size() && !r.scene.is_null(); ++k) {
      const QuantitySpec& q = st.quantities[k];
      try {
        if (q.reference.kind == Reference::Kind::ClosedForm) closed_form_values(q.reference, r.scene);
      } catch (const StudyError& e) {
        return bad_study(file, e.key(), e.reason() + " (run '" + p.label + "')");
      }
      if (q.kind != QuantitySpec::Kind::Column || p.expect) continue;
      const auto it = tables.find(q.file);
      if (it == tables.end())
        return bad_study(file, q.key + ".file", "no run writes " + q.file + ": run '" + p.label + "' writes " +
                                                    [&] {
                                                      std::string names;
                                                      for (const auto& [f, c] : tables) names += (names.empty() ? "" : ", ") + f;
                                                      return names;
                                                    }() + " (a scene writes crack_tips.csv with crack_tips)");
      for (const std::string& c : [&] {
             std::vector<std::string> need{q.column};
             for (const auto& [k, v] : q.where) need.push_back(k);
             return need;
           }())
        if (std::find(it->second.begin(), it->second.end(), c) == it->second.end()) {
          std::string cols;
          for (const auto& x : it->second) cols += (cols.empty() ? "" : ", ") + x;
          return bad_study(file, q.key + (c == q.column ? ".column" : ".where." + c),
                           "run '" + p.label + "' writes no column '" + c + "' in " + q.file + " (it has " + cols + ")");
        }
    }
  }
  if (check_only) {
    std::printf("study OK: %s: %zu runs of %s\n", st.title.c_str(), st.runs.size(),
                st.runs.empty() ? "" : st.runs[0].scene.filename().string().c_str());
    for (std::size_t i = 0; i < st.runs.size(); ++i)
      std::printf("  %-40s %s%s\n", st.runs[i].label.c_str(), settings_text(st.runs[i].varied).c_str(),
                  planned[i].points > 0 ? (", " + std::to_string(planned[i].points) + " points, " +
                                           std::to_string(planned[i].steps) + " steps").c_str()
                                        : "");
    return kOk;
  }

  struct sigaction sa {};
  sa.sa_handler = on_stop;
  ::sigaction(SIGINT, &sa, nullptr), ::sigaction(SIGTERM, &sa, nullptr);
  double work_total = 0, work_done = 0, wall_done = 0;
  for (const auto& p : planned) work_total += p.work();
  const auto t_study = std::chrono::steady_clock::now();
  const bool tty = isatty(fileno(stderr));  // the progress line: rewritten in place, or logged
  for (std::size_t i = 0; i < st.runs.size() && !g_stop; ++i) {
    const RunPlan& p = st.runs[i];
    RunRecord& r = runs[i];
    if (r.status == "refused") continue;  // by cleave check: nothing to run
    const fs::path dir = out / p.label;
    // Done before, with the same settings: kept. Stopped: resumed (its costs add up).
    double wall_before = 0, cpu_before = 0, peak_before = 0;
    bool resume = false;
    if (fs::exists(dir / "study_run.json")) {
      const json n = json::parse(read_text(dir / "study_run.json"), nullptr, false);
      if (!n.is_discarded() && n.value("settings", json()) == settings_json(p) && n.value("scene", "") == p.scene.string()) {
        const int code = n.value("exit_code", -1);
        if (code == 130 || code == 143) {
          resume = true;
          wall_before = n.value("wall_s", 0.0), cpu_before = n.value("cpu_s", 0.0), peak_before = n.value("peak_memory_MB", 0.0);
        } else {
          read_run_folder(r, dir);
          if (std::isfinite(r.wall_s)) work_done += planned[i].work(), wall_done += r.wall_s;
          else work_total -= planned[i].work();
          if (!quiet) std::fprintf(stderr, "study: run %zu of %zu (%s): done before, kept\n", i + 1, st.runs.size(), p.label.c_str());
          continue;
        }
      }
    }
    if (!resume && fs::exists(dir)) fs::remove_all(dir);  // another study's or an unfinished first try
    fs::create_directories(dir);
    std::vector<std::string> rargs{"run", p.scene.string(), "--out", dir.string(), "--quiet"};
    if (resume) rargs.push_back("--resume");
    if (const int n = run_threads(p, threads); n > 0) rargs.push_back("--threads"), rargs.push_back(std::to_string(n));
    for (const auto& s : set_args(p)) rargs.push_back(s);
    const std::string settings = settings_text(p.varied);
    const std::string what = p.varied.empty() || settings.size() > 60 ? p.label : settings;
    // On a terminal the line is rewritten in place; in a log (stderr not a terminal) a line every 30 s.
    double logged_at = 0;
    auto progress = [&](double run_wall) {
      if (quiet || (!tty && run_wall - logged_at < 30)) return;
      logged_at = run_wall;
      double frac = 0;
      const json rj = json::parse(read_text(dir / "run.json"), nullptr, false);
      if (!rj.is_discarded() && rj.contains("time") && rj.contains("end_time") && rj["end_time"].get<double>() > 0)
        frac = std::clamp(rj["time"].get<double>() / rj["end_time"].get<double>(), 0.0, 1.0);
      // This run's rest from its own pace; the runs after it at the pace of those done (or this one's).
      const double wi = planned[i].work(), after = work_total - work_done - wi;
      const double pace = work_done > 0 ? wall_done / work_done : frac > 0 ? run_wall / (frac * wi) : 0;
      const double rest = frac > 0.02 ? run_wall * (1 - frac) / frac : pace * wi * (1 - frac);
      std::fprintf(stderr, "%sstudy: run %zu of %zu (%s): %3.0f %%, %s; study ETA %s%s", tty ? "\r\033[K" : "", i + 1,
                   st.runs.size(), what.c_str(), 100 * frac, format_seconds(run_wall).c_str(),
                   pace > 0 ? format_seconds(rest + pace * std::max(0.0, after)).c_str() : "?", tty ? "" : "\n");
    };
    if (!quiet) std::fprintf(stderr, "study: run %zu of %zu (%s)%s\n", i + 1, st.runs.size(), what.c_str(), resume ? ": resumed" : "");
    const ChildResult c = run_child(rargs, dir / "stdout.txt", dir / "stderr.txt", progress);
    if (!quiet && tty) std::fprintf(stderr, "\r\033[K");
    r.exit_code = c.exit_code;
    r.wall_s = wall_before + c.wall_s, r.cpu_s = cpu_before + c.cpu_s, r.peak_mb = std::max(peak_before, c.peak_mb);
    r.particles = planned[i].points;
    const std::string err = read_text(dir / "stderr.txt");
    r.status = c.exit_code == 0 ? "complete" : c.exit_code == 2 ? "refused" : c.exit_code == 3 ? "aborted"
               : (c.exit_code == 130 || c.exit_code == 143) ? "stopped" : "failed";
    r.message = last_error(err);
    json note = {{"scene", p.scene.string()}, {"settings", settings_json(p)}, {"exit_code", c.exit_code},
                 {"status", r.status}, {"message", r.message}, {"wall_s", r.wall_s}, {"cpu_s", r.cpu_s},
                 {"peak_memory_MB", r.peak_mb}, {"particles", r.particles}};
    std::ofstream(dir / "study_run.json") << note.dump(2) << "\n";
    read_run_folder(r, dir);
    work_done += planned[i].work(), wall_done += c.wall_s;
    if (!quiet)
      std::fprintf(stderr, "study: run %zu of %zu (%s): %s in %s%s\n", i + 1, st.runs.size(), what.c_str(),
                   r.status.c_str(), format_seconds(c.wall_s).c_str(), r.message.empty() ? "" : (": " + r.message).c_str());
  }
  // Runs that were never reached keep "not run"; the others are measured.
  bool expectations_missed = false, failed = false;
  try {
    for (auto& r : runs) {
      if (r.status == "not run" || r.status == "stopped") continue;
      const fs::path dir = out / r.plan->label;
      if (r.status == "refused" && !fs::exists(dir)) {  // by cleave check
        judge_expectation(r, kNaN, false);
        expectations_missed = expectations_missed || r.expectation != "met";
        continue;
      }
      double drift = kNaN;
      // Only a complete run has a result to measure (an aborted one's last state is not one).
      if (r.status == "complete")
        for (const auto& q : st.quantities) r.q.push_back(measure(q, dir, r.scene));
      if (r.plan->expect) {
        QuantitySpec d;
        d.kind = QuantitySpec::Kind::EnergyDrift;
        if (r.status == "complete") {
          const Measurement m = measure(d, dir, r.scene);
          drift = m.ok() ? m.value : kNaN;
        }
        judge_expectation(r, drift, tables_hold_nan(dir));
        expectations_missed = expectations_missed || r.expectation != "met";
      } else {
        failed = failed || r.status != "complete";
      }
    }
    const auto fits = compute_errors(st, runs);
    write_study_csv(out / "study.csv", st, runs);
    write_summary(out / "summary.md", st, runs, fits, g_stop != 0);
    const auto plots = write_plots(out, st, runs, fits);
    if (!quiet) {
      std::fprintf(stderr, "study: %s written", (out / "study.csv").string().c_str());
      for (const auto& p : plots) std::fprintf(stderr, ", %s", p.filename().string().c_str());
      std::fprintf(stderr, ", summary.md\n");
    }
  } catch (const StudyError& e) {
    return bad_study(file, e.key(), e.reason());
  }
  if (g_stop) {
    std::fprintf(stderr, "cleave study: stopped; run the same command again to go on (finished runs are kept, the "
                         "stopped one resumes)\n");
    return 128 + g_stop;
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_study).count();
  std::printf("study done: %zu runs in %s; %s\n", runs.size(), format_seconds(total).c_str(),
              (out / "summary.md").string().c_str());
  if (expectations_missed || failed) {
    std::fprintf(stderr, "cleave study: %s (see %s)\n",
                 expectations_missed ? "runs missed their expectation" : "runs failed", (out / "summary.md").string().c_str());
    return kAborted;
  }
  return kOk;
}

}  // namespace cleave::app
