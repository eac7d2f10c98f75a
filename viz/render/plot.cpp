// Line plots: a vtkChartXY drawn through a vtkContextActor in the context's window.
#include "viz/render/headless.hpp"

#include <vtkAxis.h>
#include <vtkChart.h>
#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "viz/render/drawing.hpp"

namespace cleave::viz {

using namespace detail;

Image render_plot(HeadlessContext& context, const std::vector<PlotSeries>& series, const std::string& title,
                  const std::string& xlabel, const std::string& ylabel) {
  for (const auto& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("render_plot: series '" + s.name + "' has " + std::to_string(s.x.size()) +
                                  " x and " + std::to_string(s.y.size()) + " y values");
  static constexpr std::array<std::array<unsigned char, 3>, 10> palette{{{31, 119, 180},
                                                                          {214, 39, 40},
                                                                          {44, 160, 44},
                                                                          {255, 127, 14},
                                                                          {148, 103, 189},
                                                                          {140, 86, 75},
                                                                          {227, 119, 194},
                                                                          {127, 127, 127},
                                                                          {188, 189, 34},
                                                                          {23, 190, 207}}};
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
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    named = named || !s.name.empty();
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("x");
    y->SetName(s.name.empty() ? ("series " + std::to_string(k + 1)).c_str() : s.name.c_str());
    x->SetNumberOfTuples(static_cast<vtkIdType>(s.x.size()));
    y->SetNumberOfTuples(static_cast<vtkIdType>(s.y.size()));
    for (size_t i = 0; i < s.x.size(); ++i) {
      x->SetValue(static_cast<vtkIdType>(i), s.x[i]);
      y->SetValue(static_cast<vtkIdType>(i), s.y[i]);
    }
    auto table = vtkSmartPointer<vtkTable>::New();
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(table, 0, 1);
    const auto& c = palette[k % palette.size()];
    plot->SetColor(c[0], c[1], c[2], 255);
    plot->SetWidth(2.0);
    if (!s.name.empty()) plot->SetLabel(s.name);
  }
  chart->SetShowLegend(named);

  vtkNew<vtkContextScene> context_scene;
  context_scene->AddItem(chart);
  vtkNew<vtkContextActor> actor;
  actor->SetScene(context_scene);
  ren->AddActor(actor);
  context_scene->SetRenderer(ren);
  return context.capture();
}

}  // namespace cleave::viz
