// 3D particles as cubes (vtkGlyph3DMapper), crack surfaces over them, and the bands of a 2D frame.
#include "viz/render/headless.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "viz/render/drawing.hpp"

namespace cleave::viz {

using namespace detail;

Image render_particles_3d(HeadlessContext& context, const std::vector<std::array<double, 3>>& centres,
                          const std::vector<double>& edge, const std::vector<std::array<uint8_t, 3>>& colours,
                          const Camera3D& camera, const std::string& title, const std::string& time_stamp,
                          const ColorBar& colorbar, std::array<double, 3> background,
                          const std::vector<std::array<std::array<double, 3>, 3>>& crack_triangles) {
  if (edge.size() != centres.size() || colours.size() != centres.size())
    throw std::invalid_argument("render_particles_3d: " + std::to_string(centres.size()) + " centres, " +
                                std::to_string(edge.size()) + " edges, " + std::to_string(colours.size()) +
                                " colours");
  const std::string& preset = camera.preset;
  if (!camera.explicit_view && preset != "iso" && preset != "xy" && preset != "xz" && preset != "yz")
    throw std::invalid_argument("render_particles_3d: unknown camera preset '" + preset +
                                "' (iso, xy, xz, yz or an explicit view)");
  const int W = context.width(), H = context.height();
  const Layout l = make_layout(W, H, has_title_band(title, time_stamp), colorbar);

  Scene scene(context);
  scene.add(0, background);
  vtkRenderer* view = scene.add(0, background);
  set_viewport_pixels(view, W, H, 0, 0, std::max(1, W - l.cbar_band), std::max(1, H - l.title_band));
  vtkRenderer* annotations = scene.add(1, background);

  if (!centres.empty()) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(centres.size()));
    vtkNew<vtkDoubleArray> size;
    size->SetName("edge");
    size->SetNumberOfTuples(static_cast<vtkIdType>(centres.size()));
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("rgb");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(static_cast<vtkIdType>(centres.size()));
    for (size_t i = 0; i < centres.size(); ++i) {
      const auto id = static_cast<vtkIdType>(i);
      points->SetPoint(id, centres[i][0], centres[i][1], centres[i][2]);
      size->SetValue(id, edge[i]);
      for (int c = 0; c < 3; ++c) rgb->SetValue(3 * id + c, colours[i][c]);
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(points);
    pd->GetPointData()->AddArray(size);
    pd->GetPointData()->SetScalars(rgb);

    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(1);
    cube->SetYLength(1);
    cube->SetZLength(1);
    vtkNew<vtkGlyph3DMapper> mapper;
    mapper->SetInputData(pd);
    mapper->SetSourceConnection(cube->GetOutputPort());
    mapper->SetScaleArray("edge");
    mapper->SetScaleModeToScaleByMagnitude();
    mapper->ScalingOn();
    mapper->OrientOff();
    mapper->ScalarVisibilityOn();
    mapper->SetScalarModeToUsePointData();
    mapper->SetColorModeToDirectScalars();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    // ambient + diffuse = 1: a face square to the headlight shows its colour exactly.
    actor->GetProperty()->SetAmbient(0.15);
    actor->GetProperty()->SetDiffuse(0.85);
    actor->GetProperty()->SetSpecular(0);
    view->AddActor(actor);
  }

  if (!crack_triangles.empty()) {
    vtkRenderer* cracks = scene.add(1, background);
    set_viewport_pixels(cracks, W, H, 0, 0, std::max(1, W - l.cbar_band), std::max(1, H - l.title_band));
    cracks->SetActiveCamera(view->GetActiveCamera());
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> tris;
    for (const auto& t : crack_triangles) {
      tris->InsertNextCell(3);
      for (const auto& p : t) tris->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], p[2]));
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(pts);
    pd->SetPolys(tris);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.9, 0.1, 0.1);
    actor->GetProperty()->LightingOff();
    cracks->AddActor(actor);
  }

  vtkCamera* cam = view->GetActiveCamera();
  if (camera.explicit_view) {
    const auto& v = *camera.explicit_view;
    cam->ParallelProjectionOff();
    cam->SetPosition(v[0], v[1], v[2]);
    cam->SetFocalPoint(v[3], v[4], v[5]);
    cam->SetViewUp(v[6], v[7], v[8]);
    view->ResetCameraClippingRange();
  } else {
    double b[6] = {-0.5, 0.5, -0.5, 0.5, -0.5, 0.5};
    if (!centres.empty()) {
      b[0] = b[2] = b[4] = std::numeric_limits<double>::max();
      b[1] = b[3] = b[5] = std::numeric_limits<double>::lowest();
      for (size_t i = 0; i < centres.size(); ++i)
        for (int a = 0; a < 3; ++a) {
          b[2 * a] = std::min(b[2 * a], centres[i][a] - 0.5 * std::abs(edge[i]));
          b[2 * a + 1] = std::max(b[2 * a + 1], centres[i][a] + 0.5 * std::abs(edge[i]));
        }
    }
    const double c[3] = {0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
    // "iso": azimuth 50 degrees from +x towards +y, elevation 30 degrees; not the symmetric
    // (1,1,1), under which the headlight shades the three visible faces of a cube alike.
    constexpr double az = 50 * 3.14159265358979 / 180, el = 30 * 3.14159265358979 / 180;
    double dir[3] = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)}, up[3] = {0, 0, 1};
    if (preset == "xy") {
      dir[0] = 0, dir[1] = 0, dir[2] = 1;
      up[0] = 0, up[1] = 1, up[2] = 0;
    } else if (preset == "xz") {
      dir[0] = 0, dir[1] = -1, dir[2] = 0;
    } else if (preset == "yz") {
      dir[0] = 1, dir[1] = 0, dir[2] = 0;
    }
    cam->SetParallelProjection(preset != "iso");
    cam->SetFocalPoint(c[0], c[1], c[2]);
    cam->SetPosition(c[0] + dir[0], c[1] + dir[1], c[2] + dir[2]);
    cam->SetViewUp(up);
    view->ResetCamera(b);
    if (preset != "iso") {
      // ResetCamera fits the bounding sphere; fit the box's projection instead (tighter).
      const int ax_h = preset == "xy" ? 0 : (preset == "xz" ? 0 : 1);  // horizontal axis
      const int ax_v = preset == "xy" ? 1 : 2;                          // vertical axis
      const double hw = 0.5 * (b[2 * ax_h + 1] - b[2 * ax_h]), hh = 0.5 * (b[2 * ax_v + 1] - b[2 * ax_v]);
      const double vw = std::max(1, W - l.cbar_band), vh = std::max(1, H - l.title_band);
      const double scale = 1.08 * std::max(hh, hw * vh / vw);
      if (scale > 0) cam->SetParallelScale(scale);
    }
    view->ResetCameraClippingRange(b);
  }

  add_annotations(annotations, l, title, time_stamp, colorbar, background);
  return context.capture();
}

}  // namespace cleave::viz
