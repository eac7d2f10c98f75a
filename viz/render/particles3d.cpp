// 3D particles as cubes (vtkGlyph3DMapper), crack surfaces over them, and the bands of a 2D frame.
#include "viz/render/headless.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "viz/render/drawing.hpp"

namespace cleave::viz {

using namespace detail;

namespace {

// All faces in one actor, cells in order with their colours: VTK draws a mapper's cells in order and
// a fragment at the depth of one drawn before it does not replace it, so where two faces coincide
// (an unopened crack) the earlier one shows, and where they are apart the nearer one does (test
// CrackFaces3D.AnUnopenedCrackAtScaleOneIsDrawnRedAsBeforeItsFacesWereDrawnApart).
vtkSmartPointer<vtkActor> crack_actor(const CrackSurfaces3D& cracks) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> tris;
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("rgb");
  rgb->SetNumberOfComponents(3);
  for (const CrackFace3D& f : cracks.faces) {
    const vtkIdType first = pts->GetNumberOfPoints();
    for (const auto& p : f.points) pts->InsertNextPoint(p[0], p[1], p[2]);
    std::array<uint8_t, 3> c;
    for (std::size_t k = 0; k < 3; ++k) c[k] = uint8_t(std::lround(255 * std::clamp(f.colour[k], 0.0, 1.0)));
    for (const auto& t : f.triangles) {
      if (t[0] >= f.points.size() || t[1] >= f.points.size() || t[2] >= f.points.size()) continue;
      const vtkIdType ids[3] = {first + vtkIdType(t[0]), first + vtkIdType(t[1]), first + vtkIdType(t[2])};
      tris->InsertNextCell(3, ids);
      rgb->InsertNextTypedTuple(c.data());
    }
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(tris);
  pd->GetCellData()->SetScalars(rgb);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->ScalarVisibilityOn();
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  if (cracks.shaded) {
    // Smooth point normals per face (faces share no points), so a bulging face shades smoothly.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(pd);
    normals->SplittingOff();
    normals->ConsistencyOff();
    normals->ComputePointNormalsOn();
    normals->Update();
    mapper->SetInputData(normals->GetOutput());
    actor->GetProperty()->SetAmbient(0.4);
    actor->GetProperty()->SetDiffuse(0.6);
    actor->GetProperty()->SetSpecular(0);
  } else {
    mapper->SetInputData(pd);
    actor->GetProperty()->LightingOff();
  }
  return actor;
}

}  // namespace

Image render_particles_3d(HeadlessContext& context, const std::vector<std::array<double, 3>>& centres,
                          const std::vector<double>& edge, const std::vector<std::array<uint8_t, 3>>& colours,
                          const Camera3D& camera, const std::string& title, const std::string& time_stamp,
                          const ColorBar& colorbar, std::array<double, 3> background,
                          const CrackSurfaces3D& cracks) {
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

  if (!cracks.faces.empty()) {
    vtkRenderer* layer = scene.add(1, background);
    set_viewport_pixels(layer, W, H, 0, 0, std::max(1, W - l.cbar_band), std::max(1, H - l.title_band));
    layer->SetActiveCamera(view->GetActiveCamera());
    layer->AddActor(crack_actor(cracks));
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
