#include "study/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "libmpm/reference/closed_form.hpp"
#include "viz/render/headless.hpp"
#include "viz/render/image.hpp"

namespace fs = std::filesystem;

namespace cleave::study {
namespace {

std::string num(double v, const char* f = "%.6g") {
  if (!std::isfinite(v)) return "";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : c == '\n' ? std::string(" ") : std::string(1, c);
  return o + "\"";
}

const nlohmann::json* varied_value(const RunRecord& r, const std::string& key) {
  for (const auto& s : r.plan->varied)
    if (s.key == key) return &s.value;
  return nullptr;
}

// The study's columns: the varied keys, then any key a run's own "set" adds.
std::vector<std::string> setting_columns(const Study& st, const std::vector<RunRecord>& runs) {
  std::vector<std::string> cols = st.varied_keys;
  for (const auto& r : runs)
    for (const auto& s : r.plan->varied)
      if (std::find(cols.begin(), cols.end(), s.key) == cols.end()) cols.push_back(s.key);
  return cols;
}

std::string reference_text(const QuantitySpec& q) {
  switch (q.reference.kind) {
    case Reference::Kind::ClosedForm: return "closed form `" + q.reference.closed_form + "`: " +
                                             reference::make_closed_form(q.reference.closed_form)->formula();
    case Reference::Kind::Finest: return "the finest run of each series (Richardson-extrapolated from the three finest "
                                         "where they converge monotonically)";
    case Reference::Kind::Value: return "the value " + num(q.reference.value);
    case Reference::Kind::File: return "`" + q.reference.file.filename().string() + "` column " + q.reference.column;
    case Reference::Kind::Points: return "digitised fringe orders in `" + q.reference.file.filename().string() + "`";
    case Reference::Kind::Image: return "the photo `" + q.reference.file.filename().string() + "` (folded fringe orders)";
    case Reference::Kind::None: break;
  }
  return q.kind == QuantitySpec::Kind::EnergyDrift ? "the energy balance (the drift is the error)" : "none";
}

std::string what_text(const QuantitySpec& q) {
  switch (q.kind) {
    case QuantitySpec::Kind::EnergyDrift: return "energy drift: largest |E - W - (E0 - W0)| over the largest energy";
    case QuantitySpec::Kind::FringeRms: return "fringe-order RMS at t = " + num(q.at) + " s";
    case QuantitySpec::Kind::RunInfo: return "run.json `" + q.info_key + "`";
    case QuantitySpec::Kind::Column: break;
  }
  std::string w = q.file + " `" + q.column + "`";
  for (const auto& [k, v] : q.where) w += " " + k + " " + num(v);
  switch (q.when) {
    case QuantitySpec::When::Last: return w + ", last row";
    case QuantitySpec::When::At: return w + " at t = " + num(q.at) + " s";
    case QuantitySpec::When::Max: return w + ", largest magnitude";
    case QuantitySpec::When::Window: return w + ", RMS error over t = " + num(q.t0) + " to " + num(q.t1) + " s";
  }
  return w;
}

// How a run is named in the summary: its settings, or its label when they are long.
// A run the study named (its "runs" list) by that name: two such runs may set the same keys to the
// same values on different scenes (extremes.json's MPM and peridynamics "time.cfl=1"); a run of the
// study's grid by its settings.
std::string run_name(const RunRecord& r) {
  const std::string s = settings_text(r.plan->varied);
  return r.plan->named || s.empty() || s.size() > 60 ? r.plan->label : s;
}

std::string duration(double s) {
  if (!std::isfinite(s)) return "";
  return s < 120 ? num(s, "%.1f s") : s < 7200 ? num(s / 60, "%.1f min") : num(s / 3600, "%.2f h");
}

// "mpm.shape_function" -> "shape_function"
std::string short_key(const std::string& k) {
  const auto dot = k.rfind('.');
  return dot == std::string::npos ? k : k.substr(dot + 1);
}

// A series' legend entry: its values ("linear, USAVG"), the keys being in the title.
std::string legend_text(const Study& st, const RunRecord& r) {
  std::string t;
  for (const auto& k : st.series_keys)
    if (const auto* v = varied_value(r, k)) t += (t.empty() ? "" : ", ") + value_text(*v);
  return t;
}

bool has_errors(const std::vector<RunRecord>& runs, std::size_t k) {
  for (const auto& r : runs)
    if (k < r.error.size() && std::isfinite(r.error[k])) return true;
  return false;
}

}  // namespace

void write_study_csv(const fs::path& file, const Study& st, const std::vector<RunRecord>& runs) {
  std::ofstream o(file);
  const auto cols = setting_columns(st, runs);
  o << "run";
  for (const auto& c : cols) o << "," << csv_text(c);
  o << ",status,exit_code,steps,particles,wall_s,cpu_s,peak_memory_MB";
  for (const auto& q : st.quantities) o << "," << csv_text(q.name) << "," << csv_text(q.name + "_error");
  bool expect = false;
  for (const auto& r : runs) expect = expect || r.plan->expect.has_value();
  if (expect) o << ",expected,expectation";
  o << ",message\n";
  for (const auto& r : runs) {
    o << csv_text(r.plan->label);
    for (const auto& c : cols) {
      const auto* v = varied_value(r, c);
      o << "," << (v ? csv_text(value_text(*v)) : "");
    }
    o << "," << r.status << "," << (r.exit_code >= 0 ? std::to_string(r.exit_code) : "") << ","
      << (r.steps >= 0 ? std::to_string(r.steps) : "") << "," << (r.particles >= 0 ? std::to_string(r.particles) : "")
      << "," << num(r.wall_s, "%.3f") << "," << num(r.cpu_s, "%.3f") << "," << num(r.peak_mb, "%.1f");
    for (std::size_t k = 0; k < st.quantities.size(); ++k) {
      const bool ok = k < r.q.size() && r.q[k].ok();
      o << "," << (ok ? num(r.q[k].value, "%.10g") : "") << "," << (k < r.error.size() ? num(r.error[k], "%.6g") : "");
    }
    if (expect) o << "," << (r.plan->expect ? r.plan->expect->outcome : "") << "," << csv_text(r.expectation);
    std::string msg = r.message;
    for (std::size_t k = 0; k < r.q.size(); ++k)
      if (!r.q[k].ok()) msg += (msg.empty() ? "" : "; ") + st.quantities[k].name + ": " + r.q[k].problem;
    o << "," << csv_text(msg) << "\n";
  }
  if (!o) throw std::runtime_error(file.string() + ": cannot write");
}

void write_summary(const fs::path& file, const Study& st, const std::vector<RunRecord>& runs,
                   const std::vector<OrderFit>& fits, bool stopped) {
  std::ofstream o(file);
  o << "# " << st.title << "\n\n";
  if (!st.description.empty()) o << st.description << "\n\n";
  int done = 0, failed = 0;
  double wall = 0;
  for (const auto& r : runs) {
    done += r.status != "not run";
    failed += r.status != "complete" && r.status != "not run";
    if (std::isfinite(r.wall_s)) wall += r.wall_s;
  }
  o << "Study `" << st.file.filename().string() << "`: " << runs.size() << " runs, " << done << " ran ("
    << duration(wall) << " of runs)" << (stopped ? "; **the study was stopped before the rest ran** (run it again "
                                                   "to go on)" : "")
    << ". Every figure: `study.csv`.\n\n";
  for (std::size_t k = 0; k < st.quantities.size(); ++k) {
    const auto& q = st.quantities[k];
    o << "## " << q.name << "\n\n" << what_text(q) << "; reference: " << reference_text(q) << ".\n\n";
    if (!has_errors(runs, k)) {
      o << "No errors (no reference, or no run measured it).\n\n";
      continue;
    }
    for (double tol : q.tolerances) {
      const RunRecord* best = nullptr;
      for (const auto& r : runs)
        if (k < r.error.size() && r.error[k] <= tol && std::isfinite(r.wall_s) && (!best || r.wall_s < best->wall_s))
          best = &r;
      const std::string t = q.kind == QuantitySpec::Kind::FringeRms ? num(tol) + " fringe" : num(100 * tol) + " %";
      if (best)
        o << "- within " << t << ": cheapest **" << run_name(*best)
          << "** (error " << (q.kind == QuantitySpec::Kind::FringeRms ? num(best->error[k], "%.3g")
                                                                       : num(100 * best->error[k], "%.3g") + " %")
          << ", " << duration(best->wall_s) << ")\n";
      else
        o << "- within " << t << ": no run meets it\n";
    }
    bool any_fit = false;
    for (const auto& f : fits)
      if (f.quantity == q.name) {
        if (!any_fit) o << (q.tolerances.empty() ? "" : "\n") << "| series | runs fitted | observed order | Richardson value | its order |\n|---|---|---|---|---|\n";
        any_fit = true;
        const std::string rich = std::isfinite(f.richardson) ? num(f.richardson)
                                 : std::isfinite(f.richardson_order) ? "not asymptotic (the finest run is the reference)"
                                                                      : "";
        o << "| " << (f.series.empty() ? "all" : f.series) << " | " << f.points << " | " << num(f.order, "%.2f") << " | "
          << rich << " | " << num(f.richardson_order, "%.2f") << " |\n";
      }
    o << "\n";
  }
  o << "## Runs\n\n| run | status | wall | steps | particles |";
  for (const auto& q : st.quantities) o << " " << q.name << " | error |";
  o << "\n|---|---|---|---|---|";
  for (std::size_t k = 0; k < st.quantities.size(); ++k) o << "---|---|";
  o << "\n";
  for (const auto& r : runs) {
    o << "| " << run_name(r) << " | " << r.status << " | "
      << duration(r.wall_s) << " | " << (r.steps >= 0 ? std::to_string(r.steps) : "") << " | "
      << (r.particles >= 0 ? std::to_string(r.particles) : "") << " |";
    for (std::size_t k = 0; k < st.quantities.size(); ++k) {
      const bool ok = k < r.q.size() && r.q[k].ok();
      o << " " << (ok ? num(r.q[k].value, "%.5g") : "") << " | "
        << (k < r.error.size() && std::isfinite(r.error[k])
                ? (st.quantities[k].kind == QuantitySpec::Kind::FringeRms ? num(r.error[k], "%.3g")
                                                                          : num(100 * r.error[k], "%.3g") + " %")
                : "")
        << " |";
    }
    o << "\n";
  }
  std::ostringstream bad;
  for (const auto& r : runs) {
    const bool as_expected = r.plan->expect && r.expectation == "met";  // a refusal the suite wanted
    if (r.status != "complete" && r.status != "not run" && !as_expected)
      bad << "- " << r.plan->label << ": " << r.status << " (exit " << r.exit_code << "): " << r.message << "\n";
    if (!r.expectation.empty() && r.expectation != "met") bad << "- " << r.plan->label << ": " << r.expectation << "\n";
    for (std::size_t k = 0; k < r.q.size(); ++k)
      if (!r.q[k].ok() && r.status == "complete")
        bad << "- " << r.plan->label << ": " << st.quantities[k].name << " not measured: " << r.q[k].problem << "\n";
  }
  bool expect = false;
  int met = 0, judged = 0;
  for (const auto& r : runs)
    if (r.plan->expect) expect = true, judged += !r.expectation.empty(), met += r.expectation == "met";
  if (expect) o << "\nExpectations met: " << met << " of " << judged << " runs judged.\n";
  if (!bad.str().empty()) o << "\n## Runs that failed, stopped or missed\n\n" << bad.str();
  if (!o) throw std::runtime_error(file.string() + ": cannot write");
}

std::vector<fs::path> write_plots(const fs::path& dir, const Study& st, const std::vector<RunRecord>& runs,
                                  const std::vector<OrderFit>& fits) {
  std::vector<fs::path> written;
  bool first = true;
  viz::HeadlessContext ctx(1100, 750);
  for (std::size_t k = 0; k < st.quantities.size(); ++k) {
    if (!has_errors(runs, k)) continue;
    const auto& q = st.quantities[k];
    const std::string suffix = first ? "" : "_" + q.name;
    first = false;
    const std::string err_label = q.kind == QuantitySpec::Kind::FringeRms ? q.name + " RMS (fringes)"
                                                                          : q.name + " relative error";
    // Lines: one per series, points in order of cell size (coarse first), labelled by it.
    std::map<std::string, std::vector<const RunRecord*>> groups;
    for (const auto& r : runs)
      if (k < r.error.size() && std::isfinite(r.error[k]) && r.error[k] > 0) groups[series_of(st, r)].push_back(&r);
    std::vector<viz::PlotSeries> work, conv;
    for (auto& [name, g] : groups) {
      std::stable_sort(g.begin(), g.end(), [&](auto* a, auto* b) { return cell_of(st, *a) > cell_of(st, *b); });
      viz::PlotSeries w, c;
      const std::string legend = legend_text(st, *g.front());
      w.name = legend.empty() ? q.name : legend;
      w.markers = true;
      for (const auto* r : g) {
        w.x.push_back(r->wall_s), w.y.push_back(r->error[k]);
        const double h = cell_of(st, *r);
        w.point_labels.push_back(std::isfinite(h) ? num(h, "%g") : r->plan->label);
        if (std::isfinite(h)) c.x.push_back(h), c.y.push_back(r->error[k]);
      }
      if (w.x.size() < 2) w.line = viz::PlotSeries::Line::None;
      work.push_back(std::move(w));
      std::reverse(c.x.begin(), c.x.end()), std::reverse(c.y.begin(), c.y.end());  // fine to coarse
      if (c.x.size() >= 2) {
        c.name = legend.empty() ? q.name : legend;
        for (const auto& f : fits)
          if (f.quantity == q.name && f.series == name && std::isfinite(f.order))
            c.name += " (order " + num(f.order, "%.2f") + ")";
        c.markers = true;
        conv.push_back(std::move(c));
      }
    }
    viz::PlotLayout log_log{viz::PlotLegend::Right, 0.08};
    log_log.log_x = log_log.log_y = true;
    std::string lines;
    for (const auto& k : st.series_keys) lines += (lines.empty() ? "" : ", ") + short_key(k);
    const std::string title = q.name + (lines.empty() ? "" : " (lines: " + lines + ")");
    const std::string points = st.cell_key.empty() ? "" : "; points labelled by " + short_key(st.cell_key);
    const fs::path wp = dir / ("work_precision" + suffix + ".png");
    viz::write_png(wp, viz::render_plot(ctx, work, title, "wall time (s)" + points, err_label, log_log));
    written.push_back(wp);
    if (!conv.empty()) {
      const fs::path cp = dir / ("convergence" + suffix + ".png");
      viz::write_png(cp, viz::render_plot(ctx, conv, title, short_key(st.cell_key) + " (cell size, scene units)",
                                          err_label, log_log));
      written.push_back(cp);
    }
  }
  return written;
}

}  // namespace cleave::study
