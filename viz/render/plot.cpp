// Line plots: a vtkChartXY drawn through a vtkContextActor in the context's window.
#include "viz/render/headless.hpp"

#include <vtkAxis.h>
#include <vtkChart.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkStringArray.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "viz/render/drawing.hpp"

namespace cleave::viz {

using namespace detail;

namespace {

constexpr std::array<std::array<unsigned char, 3>, 10> kPalette{{{31, 119, 180},
                                                                 {214, 39, 40},
                                                                 {44, 160, 44},
                                                                 {255, 127, 14},
                                                                 {148, 103, 189},
                                                                 {140, 86, 75},
                                                                 {227, 119, 194},
                                                                 {127, 127, 127},
                                                                 {188, 189, 34},
                                                                 {23, 190, 207}}};

bool finite_point(const PlotSeries& s, std::size_t i) { return std::isfinite(s.x[i]) && std::isfinite(s.y[i]); }

// A logarithmic axis is drawn as a linear one of log10(value) with ticks labelled by the values
// (VTK's own log axes label only whole decades); a point it cannot show (<= 0) is not finite there.
std::vector<PlotSeries> drawable(const std::vector<PlotSeries>& series, const PlotLayout& layout) {
  std::vector<PlotSeries> out = series;
  for (auto& s : out)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (layout.log_x) s.x[i] = s.x[i] > 0 ? std::log10(s.x[i]) : NAN;
      if (layout.log_y) s.y[i] = s.y[i] > 0 ? std::log10(s.y[i]) : NAN;
    }
  return out;
}

// Ticks of a logarithmic axis spanning [lo, hi] in decades: 1-2-5 in each decade, or every digit
// when that leaves fewer than three, or decades alone when it gives more than twelve.
void set_log_ticks(vtkAxis* axis, double lo, double hi) {
  std::vector<double> ticks;
  for (const std::vector<int>& mantissas : {std::vector<int>{1, 2, 5}, std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
    ticks.clear();
    for (int k = static_cast<int>(std::floor(lo)) - 1; k <= static_cast<int>(std::ceil(hi)); ++k)
      for (int m : mantissas) {
        const double t = std::log10(m) + k;
        if (t >= lo - 1e-9 && t <= hi + 1e-9) ticks.push_back(t);
      }
    if (ticks.size() >= 3) break;
  }
  if (ticks.size() > 12) {
    ticks.clear();
    for (int k = static_cast<int>(std::ceil(lo)); k <= static_cast<int>(std::floor(hi)); ++k) ticks.push_back(k);
  }
  vtkNew<vtkDoubleArray> pos;
  vtkNew<vtkStringArray> labels;
  for (double t : ticks) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", std::pow(10.0, t));
    pos->InsertNextValue(t);
    labels->InsertNextValue(b);
  }
  axis->SetCustomTickPositions(pos, labels);
}

// Where a (drawn) data value falls on an axis, in the scene's pixels, after the chart has been drawn.
double axis_pixel(vtkAxis* axis, int along, double v) {
  const float* p1 = axis->GetPoint1();
  const float* p2 = axis->GetPoint2();
  const double lo = axis->GetMinimum(), hi = axis->GetMaximum();
  return p1[along] + (v - lo) / (hi - lo) * (p2[along] - p1[along]);
}

}  // namespace

std::array<unsigned char, 3> plot_colour(std::size_t k) { return kPalette[k % kPalette.size()]; }

Image render_plot(HeadlessContext& context, const std::vector<PlotSeries>& given, const std::string& title,
                  const std::string& xlabel, const std::string& ylabel, const PlotLayout& layout) {
  const std::vector<PlotSeries> series = drawable(given, layout);
  for (const auto& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("render_plot: series '" + s.name + "' has " + std::to_string(s.x.size()) +
                                  " x and " + std::to_string(s.y.size()) + " y values");
  const int H = context.height();
  const int title_font = std::clamp(static_cast<int>(std::lround(0.04 * H)), 10, 72);
  const int label_font = std::max(9, static_cast<int>(std::lround(0.7 * title_font)));
  const std::array<double, 3> white{1, 1, 1};

  Scene scene(context);
  vtkRenderer* ren = scene.add(0, white);

  vtkNew<vtkChartXY> chart;
  chart->SetTitle(title);
  configure_text(chart->GetTitleProperties(), title_font, {0, 0, 0});
  for (int a : {vtkAxis::BOTTOM, vtkAxis::LEFT}) {
    vtkAxis* axis = chart->GetAxis(a);
    axis->SetTitle(a == vtkAxis::BOTTOM ? xlabel : ylabel);
    configure_text(axis->GetTitleProperties(), label_font, {0, 0, 0});
    configure_text(axis->GetLabelProperties(), std::max(8, label_font - 2), {0, 0, 0});
    if (a == vtkAxis::LEFT) axis->GetTitleProperties()->SetOrientation(90);
    axis->GetTitleProperties()->SetBold(true);
  }
  bool named = false;
  std::vector<vtkSmartPointer<vtkTable>> tables;
  const float marker_size = static_cast<float>(std::max(7, label_font / 2));
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    named = named || !s.name.empty();
    const std::string y_name = s.name.empty() ? ("series " + std::to_string(k + 1)) : s.name;
    const auto& c = s.colour ? *s.colour : kPalette[k % kPalette.size()];
    // One vtkPlot per run of finite points (the whole series when all are finite, as plots always
    // were); only the first of a series shows in the legend.
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // [begin, end)
    bool all_finite = true;
    for (std::size_t i = 0; i < s.x.size(); ++i) all_finite = all_finite && finite_point(s, i);
    if (all_finite || s.line == PlotSeries::Line::None) {
      runs.push_back({0, s.x.size()});
    } else {
      for (std::size_t i = 0; i < s.x.size();) {
        while (i < s.x.size() && !finite_point(s, i)) ++i;
        const std::size_t b = i;
        while (i < s.x.size() && finite_point(s, i)) ++i;
        if (i > b) runs.push_back({b, i});
      }
    }
    bool first = true;
    for (const auto& [b, e] : runs) {
      vtkNew<vtkDoubleArray> x, y;
      x->SetName("x");
      y->SetName(y_name.c_str());
      std::vector<std::size_t> idx;
      for (std::size_t i = b; i < e; ++i)
        if (all_finite || finite_point(s, i)) idx.push_back(i);
      x->SetNumberOfTuples(static_cast<vtkIdType>(idx.size()));
      y->SetNumberOfTuples(static_cast<vtkIdType>(idx.size()));
      for (std::size_t j = 0; j < idx.size(); ++j) {
        x->SetValue(static_cast<vtkIdType>(j), s.x[idx[j]]);
        y->SetValue(static_cast<vtkIdType>(j), s.y[idx[j]]);
      }
      auto table = vtkSmartPointer<vtkTable>::New();
      table->AddColumn(x);
      table->AddColumn(y);
      tables.push_back(table);
      // A point left alone between gaps has no line to draw: a cross shows it.
      const bool points = s.line == PlotSeries::Line::None || (!all_finite && idx.size() == 1);
      vtkPlot* plot = chart->AddPlot(points ? vtkChart::POINTS : vtkChart::LINE);
      plot->SetInputData(table, 0, 1);
      plot->SetColor(c[0], c[1], c[2], 255);
      plot->SetWidth(2.0);
      if (s.line == PlotSeries::Line::Dashed) plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
      if (points || s.markers) {
        auto* pp = vtkPlotPoints::SafeDownCast(plot);
        if (pp) pp->SetMarkerStyle(vtkPlotPoints::CROSS), pp->SetMarkerSize(marker_size);
      }
      if (!s.name.empty()) plot->SetLabel(s.name);
      if (!first) plot->SetLegendVisibility(false);
      first = false;
    }
  }
  chart->SetShowLegend(named);
  if (layout.legend == PlotLegend::Right) {
    chart->GetLegend()->SetInline(false);
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
    chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  }

  if (layout.margin > 0) {
    // The finite points' box, widened by the margin on each side (of a tenth of the value when flat).
    std::array<double, 4> box{INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (const auto& s : series)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (finite_point(s, i)) {
          box[0] = std::min(box[0], s.x[i]), box[1] = std::max(box[1], s.x[i]);
          box[2] = std::min(box[2], s.y[i]), box[3] = std::max(box[3], s.y[i]);
        }
    for (int a : {0, 1}) {
      double lo = box[2 * a], hi = box[2 * a + 1];
      if (!(lo <= hi)) continue;  // no finite point
      const bool log = a == 0 ? layout.log_x : layout.log_y;
      const double span = hi > lo ? hi - lo : log ? 0.3 : std::max(std::abs(lo), 1e-30) * 0.1;
      lo -= layout.margin * span, hi += layout.margin * span;
      vtkAxis* axis = chart->GetAxis(a == 0 ? vtkAxis::BOTTOM : vtkAxis::LEFT);
      axis->SetBehavior(vtkAxis::FIXED);
      axis->SetRange(lo, hi);
    }
  }

  for (int a : {0, 1}) {
    if (!(a == 0 ? layout.log_x : layout.log_y)) continue;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& s : series)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (finite_point(s, i)) lo = std::min(lo, a == 0 ? s.x[i] : s.y[i]), hi = std::max(hi, a == 0 ? s.x[i] : s.y[i]);
    vtkAxis* axis = chart->GetAxis(a == 0 ? vtkAxis::BOTTOM : vtkAxis::LEFT);
    if (axis->GetBehavior() == vtkAxis::FIXED) lo = axis->GetMinimum(), hi = axis->GetMaximum();
    if (lo <= hi) set_log_ticks(axis, lo, hi);
  }

  vtkNew<vtkContextScene> context_scene;
  context_scene->AddItem(chart);
  vtkNew<vtkContextActor> actor;
  actor->SetScene(context_scene);
  ren->AddActor(actor);
  context_scene->SetRenderer(ren);
  bool labelled = false;
  for (const auto& s : series) labelled = labelled || !s.point_labels.empty();
  if (!labelled) return context.capture();
  // Point labels go where the first drawing put the axes: text actors in display pixels.
  context.capture();
  std::vector<vtkSmartPointer<vtkTextActor>> texts;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    if (!s.point_labels.empty() && s.point_labels.size() != s.x.size())
      throw std::invalid_argument("render_plot: series '" + s.name + "' has " + std::to_string(s.point_labels.size()) +
                                  " point labels for " + std::to_string(s.x.size()) + " points");
    const auto& c = s.colour ? *s.colour : kPalette[k % kPalette.size()];
    for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
      if (s.point_labels[i].empty() || !finite_point(s, i)) continue;
      auto t = vtkSmartPointer<vtkTextActor>::New();
      t->SetInput(s.point_labels[i].c_str());
      configure_text(t->GetTextProperty(), std::max(8, label_font - 3), {c[0] / 255.0, c[1] / 255.0, c[2] / 255.0});
      t->SetDisplayPosition(static_cast<int>(axis_pixel(chart->GetAxis(vtkAxis::BOTTOM), 0, s.x[i])) + 5,
                            static_cast<int>(axis_pixel(chart->GetAxis(vtkAxis::LEFT), 1, s.y[i])) + 4);
      ren->AddActor2D(t);
      texts.push_back(t);
    }
  }
  return context.capture();
}

}  // namespace cleave::viz
