// cleave-front-history: K_I against time at one front node of several runs, in one plot (the
// figures of docs/validation.md, "Crack-front parameters": seed 000 fig. 5, the rod's K_I(t) at its
// deepest point for three cell sizes, and figs. 7-8, for three contour radii (K_I at a mode-I node:
// J = K_I^2 (1 - nu^2) / E).
// Usage: cleave-front-history OUT.png --node last|N [--normalise K] [--title T]
//            LABEL=RUN_DIR ...
// Each RUN_DIR/crack_fronts.csv gives one series, named LABEL: the node's value (front 0 of crack 0)
// against time in microseconds, divided by --normalise when given.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "viz/job/front_plots.hpp"
#include "viz/render/headless.hpp"

using namespace cleave::viz;

int main(int argc, char** argv) {
  try {
    std::string out, node = "last", title;
    double norm = 1.0;
    std::vector<std::pair<std::string, std::string>> runs;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + ": needs a value");
        return argv[++i];
      };
      if (a == "--node") node = value();
      else if (a == "--normalise") norm = std::stod(value());
      else if (a == "--title") title = value();
      else if (out.empty()) out = a;
      else if (const auto eq = a.find('='); eq != std::string::npos) runs.push_back({a.substr(0, eq), a.substr(eq + 1)});
      else throw std::invalid_argument(a + ": expected LABEL=RUN_DIR");
    }
    if (out.empty() || runs.empty())
      throw std::invalid_argument("usage: cleave-front-history OUT.png --node last|N [--normalise K] [--title T] "
                                  "LABEL=RUN_DIR ...");
    std::vector<PlotSeries> series;
    for (const auto& [label, dir] : runs) {
      const FrontTable t = read_crack_fronts(std::filesystem::path(dir) / "crack_fronts.csv");
      int n = 0;
      for (const auto& r : t.rows)
        if (r.crack == 0 && r.front == 0) n = std::max(n, r.node + 1);
      const int k = node == "last" ? n - 1 : std::stoi(node);
      PlotSeries s;
      s.name = label;
      for (const auto& r : t.rows)
        if (r.crack == 0 && r.front == 0 && r.node == k) {
          s.x.push_back(r.time * 1e6);
          s.y.push_back(r.K[0] / norm);
        }
      series.push_back(std::move(s));
    }
    HeadlessContext ctx(1000, 600);
    PlotLayout layout;
    layout.legend = PlotLegend::Right;
    layout.margin = 0.05;
    const std::string ylabel = norm != 1.0 ? "K_I / K_static" : "K_I (Pa m^1/2)";
    write_png(out, render_plot(ctx, series, title, "time (us)", ylabel, layout));
    std::printf("%s\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave-front-history: %s\n", e.what());
    return 2;
  }
}
