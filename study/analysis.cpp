#include "study/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace cleave::study {
namespace {

const nlohmann::json* setting(const RunRecord& r, const std::string& key) {
  for (const auto& s : r.plan->varied)
    if (s.key == key) return &s.value;
  return nullptr;
}

// The reference at time t for one run (not for the finest kind).
double reference_at(const QuantitySpec& q, const RunRecord& r, double t, const Series* file_series) {
  switch (q.reference.kind) {
    case Reference::Kind::Value: return q.reference.value;
    case Reference::Kind::ClosedForm: {
      const auto form = reference::make_closed_form(q.reference.closed_form);
      return form->value(reference::complete_values(*form, closed_form_values(q.reference, r.scene)), t);
    }
    case Reference::Kind::File: return interpolate(*file_series, t);
    default: return kNaN;
  }
}

double relative(double v, double ref) { return std::fabs(v - ref) / std::fabs(ref); }

// RMS of (y - ref(t)) over RMS of ref(t), over the window's rows.
template <class Ref>
double window_error(const Series& s, Ref&& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    const double r = ref(s.t[i]);
    num += (s.y[i] - r) * (s.y[i] - r), den += r * r;
  }
  return den > 0 ? std::sqrt(num / den) : kNaN;
}

// Least-squares slope of log e against log h.
double log_slope(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : kNaN;
}

}  // namespace

double cell_of(const Study& st, const RunRecord& r) {
  if (st.cell_key.empty()) return kNaN;
  const auto* v = setting(r, st.cell_key);
  return v && v->is_number() ? v->get<double>() : kNaN;
}

std::string series_of(const Study& st, const RunRecord& r) {
  std::vector<Setting> s;
  for (const auto& k : st.series_keys)
    if (const auto* v = setting(r, k)) s.push_back({k, *v});
  return settings_text(s);
}

bool richardson(const double h[3], const double q[3], double& order, double& extrapolated) {
  // h[0] > h[1] > h[2]. (q0 - q1) / (q1 - q2) = (h0^p - h1^p) / (h1^p - h2^p), solved for p by bisection.
  const double d01 = q[0] - q[1], d12 = q[1] - q[2];
  if (d12 == 0 || d01 == 0 || (d01 > 0) != (d12 > 0)) return false;
  const double target = d01 / d12;
  auto ratio = [&](double p) {
    return (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p));
  };
  double lo = 0.05, hi = 20;
  if ((ratio(lo) - target) * (ratio(hi) - target) > 0) return false;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((ratio(lo) - target) * (ratio(mid) - target) <= 0 ? hi : lo) = mid;
  }
  order = 0.5 * (lo + hi);
  const double C = d12 / (std::pow(h[1], order) - std::pow(h[2], order));
  extrapolated = q[2] - C * std::pow(h[2], order);
  return true;
}

std::vector<OrderFit> compute_errors(const Study& st, std::vector<RunRecord>& runs) {
  std::vector<OrderFit> fits;
  for (auto& r : runs) r.error.assign(st.quantities.size(), kNaN);
  for (std::size_t k = 0; k < st.quantities.size(); ++k) {
    const QuantitySpec& q = st.quantities[k];
    Series file_series;
    if (q.reference.kind == Reference::Kind::File) {
      try {
        const Table t = read_table(q.reference.file);
        for (const auto& c : {q.reference.time_column, q.reference.column})
          if (t.column(c) < 0) throw std::runtime_error(q.reference.file.string() + ": no column '" + c + "'");
        for (const auto& row : t.rows)
          file_series.t.push_back(row[t.column(q.reference.time_column)]), file_series.y.push_back(row[t.column(q.reference.column)]);
        if (file_series.t.empty()) throw std::runtime_error(q.reference.file.string() + ": no rows");
      } catch (const std::exception& e) {
        throw StudyError(q.reference.key + ".file", e.what());
      }
    }
    // Runs grouped by series: the finest reference and the order fits are per series.
    std::map<std::string, std::vector<RunRecord*>> groups;
    for (auto& r : runs)
      if (k < r.q.size() && r.q[k].ok()) groups[series_of(st, r)].push_back(&r);
    for (auto& [name, g] : groups) {
      std::sort(g.begin(), g.end(), [&](auto* a, auto* b) { return cell_of(st, *a) > cell_of(st, *b); });
      OrderFit fit;
      fit.quantity = q.name, fit.series = name;
      const bool by_cell = !st.cell_key.empty() && std::isfinite(cell_of(st, *g.back()));
      if (q.kind == QuantitySpec::Kind::EnergyDrift || q.kind == QuantitySpec::Kind::FringeRms) {
        for (auto* r : g) r->error[k] = r->q[k].value;  // drift and fringe RMS are errors themselves
      } else if (q.reference.kind == Reference::Kind::Finest) {
        const RunRecord& finest = *g.back();
        double ref = finest.q[k].value;
        if (g.size() >= 3 && q.when != QuantitySpec::When::Window) {
          const std::size_t n = g.size();
          const double h[3] = {cell_of(st, *g[n - 3]), cell_of(st, *g[n - 2]), cell_of(st, *g[n - 1])};
          const double v[3] = {g[n - 3]->q[k].value, g[n - 2]->q[k].value, g[n - 1]->q[k].value};
          // Trusted only where the extrapolation moves the value less than the last refinement did: a
          // larger step means the runs are not yet in the asymptotic range (for halving cells, p < 1).
          if (richardson(h, v, fit.richardson_order, fit.richardson) &&
              std::fabs(fit.richardson - v[2]) <= std::fabs(v[2] - v[1]) * (1 + 1e-12))
            ref = fit.richardson;
          else
            fit.richardson = kNaN;
        }
        for (auto* r : g) {
          if (q.when == QuantitySpec::When::Window) {
            r->error[k] = window_error(r->q[k].series, [&](double t) { return interpolate(finest.q[k].series, t); });
          } else {
            r->error[k] = relative(r->q[k].value, ref);
          }
        }
      } else if (q.reference.kind != Reference::Kind::None) {
        for (auto* r : g) {
          if (q.when == QuantitySpec::When::Window) {
            r->error[k] = window_error(r->q[k].series, [&](double t) { return reference_at(q, *r, t, &file_series); });
          } else {
            r->error[k] = relative(r->q[k].value, reference_at(q, *r, r->q[k].time, &file_series));
          }
        }
      }
      if (by_cell) {
        std::vector<double> h, e;
        // Against the finest run itself, the finest's error is no error: leave it out of the fit.
        const std::size_t n = q.reference.kind == Reference::Kind::Finest && std::isnan(fit.richardson) ? g.size() - 1 : g.size();
        for (std::size_t i = 0; i < n; ++i)
          if (std::isfinite(g[i]->error[k]) && g[i]->error[k] > 0) h.push_back(cell_of(st, *g[i])), e.push_back(g[i]->error[k]);
        fit.points = static_cast<int>(h.size());
        if (h.size() >= 2) fit.order = log_slope(h, e);
        fits.push_back(fit);
      }
    }
  }
  return fits;
}

void judge_expectation(RunRecord& r, double drift, bool nan_found) {
  if (!r.plan->expect) return;
  const Expectation& x = *r.plan->expect;
  auto miss = [&](const std::string& why) { r.expectation = "MISSED: " + why; };
  r.expectation = "met";
  if (nan_found && r.status == "complete") return miss("a table holds NaN or inf, yet the run says complete");
  const bool complete = r.status == "complete", stopped = r.status == "aborted" && r.exit_code == 3,
             refused = r.status == "refused" && r.exit_code == 2;
  if (x.outcome == "complete" && !complete) return miss("expected to complete; " + r.status + ": " + r.message);
  if (x.outcome == "stop" && !stopped) return miss("expected to stop with exit 3; " + r.status);
  if (x.outcome == "refuse" && !refused) return miss("expected to be refused (exit 2); " + r.status);
  if (x.outcome == "complete_or_stop" && !complete && !stopped)
    return miss("expected to complete or stop with exit 3; " + r.status + ": " + r.message);
  if (!x.cause.empty() && !complete && r.message.find(x.cause) == std::string::npos)
    return miss("the message does not name '" + x.cause + "': " + r.message);
  if (complete && x.energy_drift && !(drift <= *x.energy_drift)) {
    char b[160];
    std::snprintf(b, sizeof b, "energy drift %.3g above %.3g", drift, *x.energy_drift);
    return miss(b);
  }
}

}  // namespace cleave::study
