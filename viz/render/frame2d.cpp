// A 2D frame: the field image as an unlit texture in its viewport, overlays, and the bands around
// it (title and time stamp, colour bar, scale bar).
#include "viz/render/headless.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "viz/render/drawing.hpp"
#include "viz/render/ticks.hpp"

namespace cleave::viz {

using namespace detail;

namespace {
Layout frame_layout(int width, int height, const Frame2D& f) {
  return make_layout(width, height, has_title_band(f.title, f.time_stamp), f.colorbar, f.text_size, f.scale_bar);
}
}  // namespace

PixelRect frame_2d_field_viewport(int width, int height, const Frame2D& f) {
  if (!(f.x1 > f.x0) || !(f.y1 > f.y0))
    throw std::invalid_argument("Frame2D: empty model window [" + std::to_string(f.x0) + ", " + std::to_string(f.x1) +
                                "] x [" + std::to_string(f.y0) + ", " + std::to_string(f.y1) + "]");
  const Layout l = frame_layout(width, height, f);
  const int ax = l.margin, ay = l.title_band + l.margin;
  const int aw = std::max(1, width - l.cbar_band - 2 * l.margin);
  const int ah = std::max(1, height - l.title_band - l.bottom_band - 2 * l.margin);
  const double aspect = (f.x1 - f.x0) / (f.y1 - f.y0);
  double w = aw, h = aw / aspect;
  if (h > ah) {
    h = ah;
    w = ah * aspect;
  }
  PixelRect r;
  r.width = std::max(1, static_cast<int>(std::lround(w)));
  r.height = std::max(1, static_cast<int>(std::lround(h)));
  r.x = ax + (aw - r.width) / 2;
  r.y = ay + (ah - r.height) / 2;
  return r;
}

Image render_frame_2d(HeadlessContext& context, const Frame2D& f) {
  if (!f.field.rgb.empty() || f.field.width != 0 || f.field.height != 0) check_image(f.field, "Frame2D field");
  const int W = context.width(), H = context.height();
  const PixelRect vp = frame_2d_field_viewport(W, H, f);
  const Layout l = frame_layout(W, H, f);

  Scene scene(context);
  scene.add(0, f.background);  // clears the whole window
  vtkRenderer* field = scene.add(0, f.background);
  set_viewport_pixels(field, W, H, vp.x, H - vp.y - vp.height, vp.width, vp.height);
  vtkRenderer* annotations = scene.add(1, f.background);

  const double extent = std::max(f.x1 - f.x0, f.y1 - f.y0);
  if (f.field.width > 0 && f.field.height > 0) {
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(f.x0, f.y0, 0);
    plane->SetPoint1(f.x1, f.y0, 0);
    plane->SetPoint2(f.x0, f.y1, 0);
    vtkNew<vtkTexture> texture;
    texture->SetInputData(to_vtk(f.field));
    texture->InterpolateOff();
    texture->RepeatOff();
    texture->EdgeClampOn();
    texture->MipmapOff();
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(plane->GetOutputPort());
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetTexture(texture);
    actor->GetProperty()->LightingOff();
    actor->GetProperty()->SetColor(1, 1, 1);
    actor->GetProperty()->SetAmbient(0);
    actor->GetProperty()->SetDiffuse(1);
    field->AddActor(actor);
  }

  // Overlays: one actor per (colour, width).
  std::map<std::tuple<double, double, double, double>, vtkSmartPointer<vtkPolyData>> groups;
  const double dz = 1e-3 * extent;
  for (const auto& line : f.overlays) {
    if (line.points.size() < 2) continue;
    auto key = std::make_tuple(line.colour[0], line.colour[1], line.colour[2], line.width);
    auto& pd = groups[key];
    if (!pd) {
      pd = vtkSmartPointer<vtkPolyData>::New();
      pd->SetPoints(vtkSmartPointer<vtkPoints>::New());
      pd->SetLines(vtkSmartPointer<vtkCellArray>::New());
    }
    vtkPoints* pts = pd->GetPoints();
    vtkCellArray* cells = pd->GetLines();
    cells->InsertNextCell(static_cast<vtkIdType>(line.points.size()));
    for (const auto& p : line.points) cells->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], dz));
  }
  for (const auto& [key, pd] : groups) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    auto* prop = actor->GetProperty();
    prop->LightingOff();
    prop->SetColor(std::get<0>(key), std::get<1>(key), std::get<2>(key));
    prop->SetAmbient(0);
    prop->SetDiffuse(1);
    prop->SetLineWidth(static_cast<float>(std::get<3>(key)));
    field->AddActor(actor);
  }

  vtkCamera* cam = field->GetActiveCamera();
  cam->ParallelProjectionOn();
  const double cx = 0.5 * (f.x0 + f.x1), cy = 0.5 * (f.y0 + f.y1);
  cam->SetFocalPoint(cx, cy, 0);
  cam->SetPosition(cx, cy, 10 * extent);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(0.5 * (f.y1 - f.y0));
  cam->SetClippingRange(5 * extent, 15 * extent);

  add_annotations(annotations, l, f.title, f.time_stamp, f.colorbar, f.background);
  if (f.scale_bar) {
    const ScaleBar sb = nice_scale_bar((f.x1 - f.x0) / vp.width, 0.2 * vp.width);
    add_scale_bar(annotations, l, vp.x, sb.length * vp.width / (f.x1 - f.x0), sb.label, f.background);
  }
  return context.capture();
}

std::array<int, 2> frame_2d_tight_size(int width, int height, const Frame2D& f) {
  const PixelRect vp = frame_2d_field_viewport(width, height, f);
  const Layout l = frame_layout(width, height, f);
  return {std::min(width, vp.width + l.cbar_band + 2 * l.margin),
          std::min(height, vp.height + l.title_band + l.bottom_band + 2 * l.margin)};
}

}  // namespace cleave::viz
