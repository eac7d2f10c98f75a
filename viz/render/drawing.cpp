// The bands around a picture and what is drawn in them: title, time stamp, colour bar with round
// ticks, scale bar (viz/render/drawing.hpp).
#include "viz/render/drawing.hpp"

#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "viz/render/ticks.hpp"

namespace cleave::viz::detail {

void check_image(const Image& image, const char* what) {
  if (image.width < 0 || image.height < 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3)
    throw std::invalid_argument(std::string(what) + ": image of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " pixels holds " +
                                std::to_string(image.rgb.size()) + " bytes, not 3 per pixel");
}

vtkSmartPointer<vtkImageData> to_vtk(const Image& image) {
  auto data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<uint8_t*>(data->GetScalarPointer());
  const size_t row = static_cast<size_t>(image.width) * 3;
  for (int j = 0; j < image.height; ++j)
    std::memcpy(dst + row * j, image.rgb.data() + row * (image.height - 1 - j), row);
  return data;
}

namespace {
double luminance(const std::array<double, 3>& c) { return 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]; }
}  // namespace

std::array<double, 3> text_colour_on(const std::array<double, 3>& background) {
  return luminance(background) > 0.5 ? std::array<double, 3>{0.05, 0.05, 0.05}
                                      : std::array<double, 3>{0.95, 0.95, 0.95};
}

void configure_text(vtkTextProperty* p, int size, const std::array<double, 3>& colour) {
  p->SetFontFamilyToArial();
  p->SetFontSize(size);
  p->SetColor(colour[0], colour[1], colour[2]);
  p->SetBold(false);
  p->SetItalic(false);
  p->SetShadow(false);
}

void set_viewport_pixels(vtkRenderer* ren, int W, int H, int x, int y_bottom, int w, int h) {
  ren->SetViewport(static_cast<double>(x) / W, static_cast<double>(y_bottom) / H, static_cast<double>(x + w) / W,
                   static_cast<double>(y_bottom + h) / H);
}

bool has_title_band(const std::string& title, const std::string& time_stamp) {
  return !title.empty() || !time_stamp.empty();
}

std::vector<double> colour_bar_ticks(const ColorBar& cb) {
  return cb.log ? log_ticks(cb.min, cb.max) : nice_ticks(cb.min, cb.max, 7);
}

Layout make_layout(int width, int height, bool title_band, const ColorBar& cb, int text_size, bool bottom_band) {
  Layout l;
  l.width = width;
  l.height = height;
  const int ref = text_size > 0 ? text_size : height;
  l.title_font = std::clamp(static_cast<int>(std::lround(0.04 * ref)), 10, 72);
  l.label_font = std::max(9, static_cast<int>(std::lround(0.62 * l.title_font)));
  l.margin = std::max(4, static_cast<int>(std::lround(0.5 * l.title_font)));
  l.title_band = title_band ? static_cast<int>(std::lround(1.8 * l.title_font)) : 0;
  l.bottom_band = bottom_band ? static_cast<int>(std::lround(2.0 * l.label_font)) : 0;
  if (cb.show) {
    l.bar_width = std::max(8, static_cast<int>(std::lround(0.035 * ref)));
    size_t chars = 4;
    for (double t : colour_bar_ticks(cb)) {
      char b[64];
      std::snprintf(b, sizeof b, "%g", t);
      chars = std::max(chars, std::strlen(b));
    }
    l.label_width = static_cast<int>(std::lround((chars + 1) * 0.62 * l.label_font)) + 4;
    l.cbar_title_width = cb.title.empty() ? 0 : static_cast<int>(std::lround(1.6 * l.label_font));
    l.cbar_band = 2 * l.margin + l.bar_width + l.label_width + l.cbar_title_width;
  }
  return l;
}

namespace {
vtkSmartPointer<vtkLookupTable> make_lookup_table(const ColorBar& cb) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  double lo = cb.min, hi = cb.max;
  if (cb.log) {
    if (hi <= 0) hi = 1;
    if (lo <= 0 || lo >= hi) lo = hi * 1e-6;
  } else if (!(hi > lo)) {
    hi = lo + (lo == 0 ? 1 : std::abs(lo) * 1e-6);
  }
  if (cb.table.empty()) {
    lut->SetNumberOfTableValues(256);
    lut->SetHueRange(0.667, 0.0);
    lut->SetRange(lo, hi);
    if (cb.log) lut->SetScaleToLog10();
    lut->Build();
  } else {
    const auto n = static_cast<vtkIdType>(std::max<size_t>(cb.table.size(), 1));
    lut->SetNumberOfTableValues(n);
    for (vtkIdType i = 0; i < n; ++i) {
      const auto& c = cb.table[std::min<size_t>(static_cast<size_t>(i), cb.table.size() - 1)];
      lut->SetTableValue(i, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, 1.0);
    }
    lut->SetRange(lo, hi);
    if (cb.log) lut->SetScaleToLog10();
  }
  return lut;
}

}  // namespace

Scene::Scene(HeadlessContext& context) : context_(context) { context_.make_current(); }
Scene::~Scene() {
  context_.make_current();
  for (auto& r : renderers_) context_.window()->RemoveRenderer(r);
}
vtkRenderer* Scene::add(int layer, const std::array<double, 3>& background) {
  auto r = vtkSmartPointer<vtkRenderer>::New();
  r->SetBackground(background[0], background[1], background[2]);
  r->SetLayer(layer);
  if (layer > 0) r->PreserveColorBufferOn();
  r->InteractiveOff();
  if (context_.window()->GetNumberOfLayers() < layer + 1) context_.window()->SetNumberOfLayers(layer + 1);
  context_.window()->AddRenderer(r);
  renderers_.push_back(r);
  return r;
}

void add_annotations(vtkRenderer* ren, const Layout& l, const std::string& title, const std::string& time_stamp,
                     const ColorBar& cb, const std::array<double, 3>& background) {
  const auto fg = text_colour_on(background);
  const double band_mid = l.height - 0.5 * l.title_band;
  if (!title.empty()) {
    vtkNew<vtkTextActor> t;
    t->SetInput(title.c_str());
    configure_text(t->GetTextProperty(), l.title_font, fg);
    t->GetTextProperty()->SetJustificationToCentered();
    t->GetTextProperty()->SetVerticalJustificationToCentered();
    t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    t->SetPosition(0.5 * l.width, band_mid);
    ren->AddActor2D(t);
  }
  if (!time_stamp.empty()) {
    vtkNew<vtkTextActor> t;
    t->SetInput(time_stamp.c_str());
    configure_text(t->GetTextProperty(), l.title_font, fg);  // as large as a title: read at print size
    t->GetTextProperty()->SetJustificationToRight();
    t->GetTextProperty()->SetVerticalJustificationToCentered();
    t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    t->SetPosition(l.width - l.margin, band_mid);
    ren->AddActor2D(t);
  }
  if (cb.show) {
    // Bar and tick labels in the right band, from just above the bottom margin to just below the
    // title band (half a label of room at both ends for the end labels).
    const double bottom = l.margin + 0.6 * l.label_font;
    const double top = l.height - l.title_band - l.margin - 0.6 * l.label_font;
    const double x = l.width - l.cbar_band + l.margin;
    const double w = l.bar_width + l.label_width;
    vtkNew<vtkScalarBarActor> bar;
    bar->SetLookupTable(make_lookup_table(cb));
    bar->SetOrientationToVertical();
    bar->SetTextPositionToSucceedScalarBar();
    bar->SetMaximumNumberOfColors(std::max<int>(256, static_cast<int>(cb.table.size())));
    // Round ticks (1-2-5 steps) rather than VTK's evenly spaced labels (2.15 / 34.2 / 66.2).
    const std::vector<double> ticks = colour_bar_ticks(cb);
    vtkNew<vtkDoubleArray> labels;
    for (double t : ticks) labels->InsertNextValue(t);
    bar->SetUseCustomLabels(true);
    bar->SetCustomLabels(labels);
    bar->SetNumberOfLabels(static_cast<int>(ticks.size()));
    bar->SetLabelFormat("%g");
    bar->UnconstrainedFontSizeOn();
    bar->SetBarRatio(l.bar_width / w);
    bar->SetTextPad(2);
    bar->DrawFrameOff();
    bar->DrawBackgroundOff();
    bar->DrawAnnotationsOff();
    bar->SetTitle(" ");
    configure_text(bar->GetLabelTextProperty(), l.label_font, fg);
    configure_text(bar->GetTitleTextProperty(), 1, fg);
    bar->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    bar->GetPositionCoordinate()->SetValue(x, bottom);
    bar->GetPosition2Coordinate()->SetCoordinateSystemToDisplay();
    bar->GetPosition2Coordinate()->SetReferenceCoordinate(nullptr);
    bar->GetPosition2Coordinate()->SetValue(x + w, top);
    ren->AddActor2D(bar);
    if (!cb.title.empty()) {
      vtkNew<vtkTextActor> t;
      t->SetInput(cb.title.c_str());
      configure_text(t->GetTextProperty(), l.label_font, fg);
      t->GetTextProperty()->SetJustificationToCentered();
      t->GetTextProperty()->SetVerticalJustificationToCentered();
      t->GetTextProperty()->SetOrientation(90);
      t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
      t->SetPosition(l.width - l.margin - 0.5 * l.cbar_title_width, 0.5 * (bottom + top));
      ren->AddActor2D(t);
    }
  }
}

void add_scale_bar(vtkRenderer* ren, const Layout& l, int x0, double pixels, const std::string& label,
                   const std::array<double, 3>& background) {
  if (l.bottom_band <= 0 || !(pixels >= 1)) return;
  const auto fg = text_colour_on(background);
  // Display coordinates have y up; the band is the picture's last rows. A bar a third of a label high.
  const double mid = 0.5 * l.bottom_band;
  const double half = std::max(1.0, std::round(0.16 * l.label_font));
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(x0, mid - half, 0);
  pts->InsertNextPoint(x0 + pixels, mid - half, 0);
  pts->InsertNextPoint(x0 + pixels, mid + half, 0);
  pts->InsertNextPoint(x0, mid + half, 0);
  vtkNew<vtkCellArray> quad;
  const vtkIdType ids[4] = {0, 1, 2, 3};
  quad->InsertNextCell(4, ids);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(quad);
  vtkNew<vtkCoordinate> display;
  display->SetCoordinateSystemToDisplay();
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(pd);
  mapper->SetTransformCoordinate(display);
  vtkNew<vtkActor2D> bar;
  bar->SetMapper(mapper);
  bar->GetProperty()->SetColor(fg[0], fg[1], fg[2]);
  ren->AddActor2D(bar);
  vtkNew<vtkTextActor> t;
  t->SetInput(label.c_str());
  configure_text(t->GetTextProperty(), l.label_font, fg);
  t->GetTextProperty()->SetJustificationToLeft();
  t->GetTextProperty()->SetVerticalJustificationToCentered();
  t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  t->SetPosition(x0 + pixels + 0.6 * l.label_font, mid);
  ren->AddActor2D(t);
}

}  // namespace cleave::viz::detail
