// K along 3D crack fronts from OUT/crack_fronts.csv (front_plots.hpp).
#include "viz/job/front_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "viz/job/colour_scale.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::array<const char*, 3> kModes{"KI", "KII", "KIII"};
const std::string kFlagged = "flagged (contour incomplete)";
const std::string kKUnit = "K (MPa m^1/2)";

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// A column by its name with its unit ("KI_Pa_sqrt_m") or its bare name ("KI"); -1 if absent.
int column(const std::vector<std::string>& h, const std::string& name, const std::string& unit) {
  auto it = unit.empty() ? h.end() : std::find(h.begin(), h.end(), name + "_" + unit);
  if (it == h.end()) it = std::find(h.begin(), h.end(), name);
  return it == h.end() ? -1 : int(it - h.begin());
}

using FrontKey = std::pair<int, int>;  // crack, front

// The rows of each front, in file order.
std::map<FrontKey, std::vector<const FrontRow*>> by_front(const FrontTable& t) {
  std::map<FrontKey, std::vector<const FrontRow*>> m;
  for (const auto& r : t.rows) m[{r.crack, r.front}].push_back(&r);
  return m;
}

std::string front_name(const FrontKey& k) {
  return "crack " + std::to_string(k.first) + " front " + std::to_string(k.second);
}

// The output time nearest `want` (the last without it).
double chosen_time(const FrontTable& t, const std::optional<double>& want) {
  std::set<double> times;
  for (const auto& r : t.rows) times.insert(r.time);
  if (!want) return *times.rbegin();
  double best = *times.begin();
  for (double v : times)
    if (std::abs(v - *want) < std::abs(best - *want)) best = v;
  return best;
}

PlotSeries dashed(PlotSeries s) {
  s.line = PlotSeries::Line::Dashed;
  return s;
}

PlotSeries flagged_series() {
  PlotSeries f;
  f.name = kFlagged;
  f.line = PlotSeries::Line::None;
  f.markers = true;
  f.colour = std::array<unsigned char, 3>{0, 0, 0};
  return f;
}

}  // namespace

FrontTable read_crack_fronts(const fs::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot be read");
  FrontTable t;
  t.file = csv;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(csv.string() + ": empty (no header line)");
  std::vector<std::string> h;
  {
    std::stringstream hs(line);
    for (std::string c; std::getline(hs, c, ',');) h.push_back(trim(c));
  }
  auto need = [&](const std::string& name, const std::string& unit) {
    const int c = column(h, name, unit);
    if (c < 0)
      throw std::runtime_error(csv.string() + ": no column '" + (unit.empty() ? name : name + "_" + unit) +
                               "' (crack_fronts.csv: time_s,crack,front,node,s_m,...,KI_Pa_sqrt_m,...,flag)");
    return c;
  };
  const int c_time = need("time", "s"), c_crack = need("crack", ""), c_front = need("front", ""),
            c_node = need("node", ""), c_s = need("s", "m");
  std::array<int, 3> c_K{}, c_ref{};
  for (int m = 0; m < 3; ++m) {
    c_K[m] = m == 0 ? need(kModes[m], "Pa_sqrt_m") : column(h, kModes[m], "Pa_sqrt_m");
    c_ref[m] = column(h, std::string(kModes[m]) + "_ref", "Pa_sqrt_m");
    t.has_K[m] = c_K[m] >= 0;
    t.has_ref[m] = c_ref[m] >= 0;
  }
  const int c_phi = column(h, "phi", "rad"), c_flag = column(h, "flag", "");
  t.has_phi = c_phi >= 0;

  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    std::vector<std::string> cells;
    for (std::size_t b = 0;;) {  // empty cells kept, a trailing one too
      const std::size_t e = line.find(',', b);
      cells.push_back(trim(line.substr(b, e == std::string::npos ? std::string::npos : e - b)));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    // A row of another length (the last line of a file the solver is still writing) is left out, as
    // the other plots leave such rows out.
    if (cells.size() != h.size()) continue;
    // An empty cell (an optional value the solver had none for) or "nan" reads as NaN.
    auto num = [&](int c) {
      if (c < 0 || cells[c].empty()) return kNaN;
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (*end != '\0')
        throw std::runtime_error(csv.string() + ":" + std::to_string(line_no) + ": column '" + h[c] + "': '" +
                                 cells[c] + "' is not a number");
      return v;
    };
    auto whole = [&](int c) {
      const double v = num(c);
      if (!std::isfinite(v) || v != std::floor(v) || v < 0 || v > 1e9)
        throw std::runtime_error(csv.string() + ":" + std::to_string(line_no) + ": column '" + h[c] + "': '" +
                                 cells[c] + "' is not an index");
      return int(v);
    };
    FrontRow r;
    r.time = num(c_time);
    if (!std::isfinite(r.time))
      throw std::runtime_error(csv.string() + ":" + std::to_string(line_no) + ": no time");
    r.crack = whole(c_crack), r.front = whole(c_front), r.node = whole(c_node);
    r.s = num(c_s);
    r.phi = num(c_phi);
    for (int m = 0; m < 3; ++m) r.K[m] = num(c_K[m]), r.K_ref[m] = num(c_ref[m]);
    const double f = c_flag < 0 ? 0.0 : num(c_flag);
    r.flag = std::isnan(f) ? 0 : f != 0 ? 1 : 0;
    t.rows.push_back(r);
  }
  return t;
}

FrontPlot k_along_front(const FrontTable& t, const FrontPlotOptions& o) {
  const bool phi = o.axis == FrontAxis::EllipseAngle;
  if (phi && !t.has_phi)
    throw std::invalid_argument("--front-axis phi: " + t.file.string() +
                                " has no phi_rad column: the ellipse angle is written only when the scene names an "
                                "elliptical (or penny) reference solution, and this one names none; use --front-axis s");
  FrontPlot p;
  if (t.rows.empty()) return p;
  const double time = chosen_time(t, o.time);
  p.title = "Stress intensity factors along the front, " + format_time(time);
  p.xlabel = phi ? "ellipse angle phi (deg)" : "arc length along the front s (mm)";
  p.ylabel = kKUnit;
  const auto fronts = by_front(t);
  const bool several = fronts.size() > 1;
  std::vector<PlotSeries> measured, reference;
  PlotSeries flagged = flagged_series();
  std::size_t f_index = 0;
  for (const auto& [key, rows] : fronts) {
    std::map<int, const FrontRow*> at;  // node -> row at the chosen time (the last written wins)
    for (const FrontRow* r : rows)
      if (r->time == time) at[r->node] = r;
    if (at.empty()) {
      ++f_index;
      continue;
    }
    std::vector<const FrontRow*> ordered;
    for (const auto& [n, r] : at) ordered.push_back(r);
    // Along the angle the nodes go in order of phi (a closed front's node 0 need not be at phi = 0).
    if (phi) {
      auto key = [](const FrontRow* r) { return std::isnan(r->phi) ? INFINITY : r->phi; };  // no angle: last
      std::stable_sort(ordered.begin(), ordered.end(), [&](auto* a, auto* b) { return key(a) < key(b); });
    }
    const std::string suffix = several ? ", " + front_name(key) : "";
    for (int m = 0; m < 3; ++m) {
      if (!t.has_K[m]) continue;
      const auto colour = plot_colour(3 * f_index + m);
      PlotSeries s, ref;
      s.name = kModes[m] + suffix;
      s.colour = ref.colour = colour;
      ref.name = kModes[m] + std::string(" reference") + suffix;
      for (const FrontRow* r : ordered) {
        const double x = phi ? r->phi * 180 / std::numbers::pi : r->s * 1e3;
        s.x.push_back(x);
        s.y.push_back(r->flag ? kNaN : r->K[m] * 1e-6);
        if (r->flag) flagged.x.push_back(x), flagged.y.push_back(r->K[m] * 1e-6);
        ref.x.push_back(x);
        ref.y.push_back(r->K_ref[m] * 1e-6);
      }
      measured.push_back(std::move(s));
      if (t.has_ref[m]) reference.push_back(dashed(std::move(ref)));
    }
    ++f_index;
  }
  p.series = std::move(measured);
  for (auto& s : reference) p.series.push_back(std::move(s));
  if (!flagged.x.empty()) p.series.push_back(std::move(flagged));
  return p;
}

FrontPlot k_against_time(const FrontTable& t, const FrontPlotOptions& o) {
  FrontPlot p;
  if (t.rows.empty()) return p;
  p.title = "KI at front nodes against time";
  p.xlabel = "time (ms)";
  p.ylabel = kKUnit;
  const auto fronts = by_front(t);
  const bool several = fronts.size() > 1;
  // A front's node count: its largest node index + 1 over all times.
  std::map<FrontKey, int> count;
  for (const auto& [key, rows] : fronts)
    for (const FrontRow* r : rows) count[key] = std::max(count[key], r->node + 1);
  if (o.nodes) {
    for (const auto& [key, n] : count)
      for (int i : *o.nodes)
        if (i < 0 || i >= n)
          throw std::invalid_argument("--front-nodes: node " + std::to_string(i) + " is out of range: " +
                                      front_name(key) + " has nodes 0 to " + std::to_string(n - 1));
  }
  std::vector<PlotSeries> measured, reference;
  PlotSeries flagged = flagged_series();
  std::size_t colour = 0;
  for (const auto& [key, rows] : fronts) {
    const int n = count[key];
    std::vector<int> nodes = o.nodes ? *o.nodes : std::vector<int>{0, n / 2, n - 1};
    std::vector<int> unique;
    for (int i : nodes)
      if (std::find(unique.begin(), unique.end(), i) == unique.end()) unique.push_back(i);
    const std::string suffix = several ? ", " + front_name(key) : "";
    for (int node : unique) {
      std::map<double, const FrontRow*> at;  // time -> the node's row (the last written wins)
      for (const FrontRow* r : rows)
        if (r->node == node) at[r->time] = r;
      PlotSeries s, ref;
      s.name = "KI node " + std::to_string(node) + suffix;
      ref.name = "KI reference node " + std::to_string(node) + suffix;
      s.colour = ref.colour = plot_colour(colour++);
      for (const auto& [time, r] : at) {
        s.x.push_back(time * 1e3);
        s.y.push_back(r->flag ? kNaN : r->K[0] * 1e-6);
        if (r->flag) flagged.x.push_back(time * 1e3), flagged.y.push_back(r->K[0] * 1e-6);
        ref.x.push_back(time * 1e3);
        ref.y.push_back(r->K_ref[0] * 1e-6);
      }
      measured.push_back(std::move(s));
      if (t.has_ref[0]) reference.push_back(dashed(std::move(ref)));
    }
  }
  // A reference that is the same at every node drawn (a penny under uniform tension) is drawn once.
  auto same = [](const PlotSeries& a, const PlotSeries& b) {
    if (a.x != b.x) return false;
    for (std::size_t i = 0; i < a.y.size(); ++i) {
      const double scale = std::max({std::abs(a.y[i]), std::abs(b.y[i]), 1e-30});
      if (!(std::abs(a.y[i] - b.y[i]) <= 1e-9 * scale) && !(std::isnan(a.y[i]) && std::isnan(b.y[i]))) return false;
    }
    return true;
  };
  if (reference.size() > 1 &&
      std::all_of(reference.begin() + 1, reference.end(), [&](const PlotSeries& r) { return same(r, reference[0]); })) {
    reference.resize(1);
    reference[0].name = "KI reference";
    reference[0].colour = std::array<unsigned char, 3>{90, 90, 90};
  }
  p.series = std::move(measured);
  for (auto& s : reference) p.series.push_back(std::move(s));
  if (!flagged.x.empty()) p.series.push_back(std::move(flagged));
  return p;
}

std::vector<FrontPlot> front_plots(const fs::path& dir, const FrontPlotOptions& o) {
  const fs::path csv = dir / "crack_fronts.csv";
  const char* opt = o.time ? "--front-time" : o.axis ? "--front-axis" : "--front-nodes";
  if (!fs::exists(csv)) {
    if (o.any())
      throw std::invalid_argument(std::string(opt) + ": there is no " + csv.string() +
                                  " (3D runs whose scene asks for crack_tips write it)");
    return {};
  }
  const FrontTable t = read_crack_fronts(csv);
  if (t.rows.empty()) {
    if (o.any()) throw std::invalid_argument(std::string(opt) + ": " + csv.string() + " has no rows");
    return {};
  }
  FrontPlot along = k_along_front(t, o), in_time = k_against_time(t, o);
  along.file = "K_front.png";
  in_time.file = "K_front_time.png";
  return {std::move(along), std::move(in_time)};
}

std::vector<fs::path> write_front_plots(HeadlessContext& ctx, const fs::path& images, const std::vector<FrontPlot>& plots) {
  std::vector<fs::path> out;
  if (!plots.empty()) fs::create_directories(images);
  for (const auto& p : plots) {
    const fs::path f = images / p.file;
    write_png(f, render_plot(ctx, p.series, p.title, p.xlabel, p.ylabel, {PlotLegend::Right, 0.05}));
    out.push_back(f);
  }
  return out;
}

}  // namespace cleave::viz
