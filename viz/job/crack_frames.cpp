// Reading OUT/cracks.pvd for drawing (viz/job/crack_frames.hpp).
#include "viz/job/crack_frames.hpp"

#include <vtkCell.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>

#include "libmpm/io/pvd_writer.hpp"

namespace cleave::viz {
namespace fs = std::filesystem;

namespace {
constexpr std::array<double, 3> kAboveColour{0.9, 0.1, 0.1};   // the crack red of 2D paths and older renders
constexpr std::array<double, 3> kBelowColour{0.1, 0.35, 0.95}; // blue: apart from red and from viridis' ends
}  // namespace

CrackFrame nearest_crack_frame(const fs::path& dir, double t) {
  CrackFrame cf;
  const fs::path pvd = dir / "cracks.pvd";
  if (!fs::exists(pvd)) return cf;
  const auto idx = io::PvdIndex::load(pvd);
  if (idx.entries().empty()) return cf;
  auto best = idx.entries().front();
  for (const auto& e : idx.entries())
    if (std::fabs(e.first - t) < std::fabs(best.first - t)) best = e;
  vtkNew<vtkXMLUnstructuredGridReader> r;
  cf.file = dir / best.second;
  r->SetFileName(cf.file.c_str());
  r->Update();
  cf.grid = r->GetOutput();
  cf.time = best.first;
  return cf;
}

bool has_crack_surfaces(vtkUnstructuredGrid* g) {
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c)
    if (g->GetCellType(c) == VTK_TRIANGLE) return true;
  return false;
}

// Cracks are written as VTK_LINE segments in path order (meshio reads no poly-lines), so a segment
// that starts where the previous one ended continues its path; a VTK_POLY_LINE cell (files of Cleave
// before issue 15) is a whole path, a vertex a one-point crack. The line cells of a 3D crack frame
// are its fronts, in 3D: no 2D paths.
std::vector<std::vector<vtkIdType>> crack_paths(vtkUnstructuredGrid* g) {
  std::vector<std::vector<vtkIdType>> paths;
  if (has_crack_surfaces(g)) return paths;
  bool open = false;  // the last path may go on with a segment
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    const int type = g->GetCellType(c);
    if (type != VTK_LINE && type != VTK_POLY_LINE && type != VTK_VERTEX) {
      open = false;
      continue;
    }
    vtkNew<vtkIdList> ids;
    g->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() == 0) continue;
    vtkIdType k = 0;
    if (type == VTK_LINE && open && paths.back().back() == ids->GetId(0)) k = 1;  // continues the path
    else paths.emplace_back();
    for (; k < ids->GetNumberOfIds(); ++k) paths.back().push_back(ids->GetId(k));
    open = type == VTK_LINE;
  }
  return paths;
}

std::vector<Polyline2D> crack_overlays(const fs::path& dir, double t) {
  const CrackFrame cf = nearest_crack_frame(dir, t);
  return cf.grid ? crack_overlays(cf.grid) : std::vector<Polyline2D>{};
}

std::vector<Polyline2D> crack_overlays(vtkUnstructuredGrid* g) {
  std::vector<Polyline2D> out;
  for (const auto& path : crack_paths(g)) {
    Polyline2D pl;
    pl.colour = kAboveColour;
    for (vtkIdType id : path) {
      double x[3];
      g->GetPoint(id, x);
      pl.points.push_back({x[0], x[1]});
    }
    out.push_back(std::move(pl));
  }
  return out;
}

CrackSurfaces crack_surfaces(vtkUnstructuredGrid* g) {
  CrackSurfaces s;
  const vtkIdType n = g->GetNumberOfPoints();
  vtkDataArray* above = g->GetPointData()->GetArray("above");
  vtkDataArray* below = g->GetPointData()->GetArray("below");
  const bool faces = above && below && above->GetNumberOfComponents() == 3 && below->GetNumberOfComponents() == 3 &&
                     above->GetNumberOfTuples() == n && below->GetNumberOfTuples() == n;
  s.above.resize(static_cast<std::size_t>(n));
  s.below.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (faces) {
      above->GetTuple(i, s.above[k].data());
      below->GetTuple(i, s.below[k].data());
    } else {
      g->GetPoint(i, s.above[k].data());
      s.below[k] = s.above[k];
    }
  }
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    if (g->GetCellType(c) != VTK_TRIANGLE) continue;
    vtkNew<vtkIdList> ids;
    g->GetCellPoints(c, ids);
    s.triangles.push_back({static_cast<std::size_t>(ids->GetId(0)), static_cast<std::size_t>(ids->GetId(1)),
                           static_cast<std::size_t>(ids->GetId(2))});
  }
  return s;
}

CrackSurfaces3D crack_faces_3d(const CrackSurfaces& s, double K) {
  CrackSurfaces3D out;
  out.shaded = K != 1;
  for (CrackFace face : {CrackFace::Above, CrackFace::Below}) {
    CrackFace3D f;
    f.points = opened_face_points(s, K, face);
    f.triangles = s.triangles;
    f.colour = face == CrackFace::Above ? kAboveColour : kBelowColour;
    out.faces.push_back(std::move(f));
  }
  return out;
}

std::vector<Polyline2D> section_overlays(const CrackSurfaces& s, double K, const std::array<double, 6>& plane) {
  std::vector<Polyline2D> out;
  // Below first, above over it: where the faces meet (the crack's front) the line is red.
  for (CrackFace face : {CrackFace::Below, CrackFace::Above})
    for (auto& line : face_section(s, K, face, {plane[0], plane[1], plane[2]}, {plane[3], plane[4], plane[5]})) {
      Polyline2D pl;
      pl.points = std::move(line);
      pl.colour = face == CrackFace::Above ? kAboveColour : kBelowColour;
      out.push_back(std::move(pl));
    }
  return out;
}

}  // namespace cleave::viz
