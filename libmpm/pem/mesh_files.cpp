// Reading a PEM mesh from a file (mesh.hpp): Gmsh's .msh through the Gmsh library (every version
// and encoding it reads), VTK's .vtu through VTK's XML reader. Both give their elements of the
// scene's dimension to the checks every PEM mesh passes (mesh_build.cpp).
#include <gmsh.h>

#include <vtkCallbackCommand.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "libmpm/core/error.hpp"
#include "libmpm/pem/gmsh_session.hpp"
#include "libmpm/pem/mesh.hpp"
#include "libmpm/pem/mesh_build.hpp"

namespace cleave::pem {
namespace {

namespace fs = std::filesystem;
using detail::Fail;
using detail::raise;
using detail::RawMesh;

// Refused before any reader sees it, as crack surface files are (crack/mesh_files.cpp): a missing
// file, a directory, a device, FIFO or socket (endless or blocking).
void check_regular_file(const std::string& file, const Fail& fail) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);  // follows links: a link to a device is a device
  if (!fs::exists(st)) raise(fail, "cannot open: " + (ec ? ec.message() : std::string("no such file")));
  if (fs::is_directory(st)) raise(fail, "cannot open: is a directory");
  if (!fs::is_regular_file(st))
    raise(fail, "not a regular file (a device, FIFO or socket); a mesh is read from a .msh or .vtu file");
}

const char* taken_kinds(int dim) {
  return dim == 2 ? "PEM takes first-order triangles and quadrangles in 2D"
                  : "PEM takes first-order tetrahedra and hexahedra in 3D";
}

std::string no_elements(int dim) {
  return dim == 2 ? "it has no 2D element (triangle or quadrangle)" : "it has no 3D element (tetrahedron or hexahedron)";
}

// --- Gmsh .msh ---------------------------------------------------------------------------------------
RawMesh read_msh(const std::string& file, int dim, const Fail& fail) {
  detail::GmshSession session;
  RawMesh raw;
  detail::gmsh_guarded(
      [&] {
        gmsh::open(file);
        if (dim == 2) {
          std::vector<int> types;
          gmsh::model::mesh::getElementTypes(types, 3);
          if (!types.empty())
            raise(fail, "it holds 3D elements; a 2D scene needs a mesh of triangles or quadrangles");
        }
        // An entity's region: its physical group; entities in none form the region "".
        gmsh::vectorpair entities;
        gmsh::model::getEntities(entities, dim);
        std::vector<std::pair<int, int>> entity_group;  // (entity, physical tag or -1)
        for (const auto& [d, tag] : entities) {
          std::vector<int> groups;
          gmsh::model::getPhysicalGroupsForEntity(d, tag, groups);
          if (groups.size() > 1) {
            std::string names;
            for (int g : groups) {
              std::string n;
              gmsh::model::getPhysicalName(d, g, n);
              names += (names.empty() ? "'" : ", '") + (n.empty() ? std::to_string(g) : n) + "'";
            }
            raise(fail, "entity " + std::to_string(tag) + " (dimension " + std::to_string(d) +
                            ") belongs to several physical groups (" + names +
                            "); each element's region must be one group");
          }
          entity_group.emplace_back(tag, groups.empty() ? -1 : groups[0]);
        }
        // Regions by physical tag, the ungrouped last; a group without a name is named by its tag.
        std::map<int, int32_t> region_of;
        for (const auto& [tag, group] : entity_group) region_of.emplace(group == -1 ? INT32_MAX : group, 0);
        for (auto& [group, index] : region_of) {
          index = static_cast<int32_t>(raw.regions.size());
          std::string name;
          if (group != INT32_MAX) gmsh::model::getPhysicalName(dim, group, name);
          raw.regions.push_back(group == INT32_MAX ? "" : name.empty() ? std::to_string(group) : name);
        }
        std::vector<std::pair<int, int32_t>> entity_regions;
        for (const auto& [tag, group] : entity_group)
          entity_regions.emplace_back(tag, region_of.at(group == -1 ? INT32_MAX : group));
        RawMesh elements = detail::gmsh_elements(dim, entity_regions, fail);
        if (elements.region.empty()) raise(fail, no_elements(dim) + detail::gmsh_complaints());
        elements.regions = std::move(raw.regions);
        raw = std::move(elements);
      },
      [&](const std::string& why) { raise(fail, "Gmsh cannot read it: " + why); });
  // Groups with elements of the dimension only (a group of boundary lines is not a region).
  std::vector<int32_t> used(raw.regions.size(), -1);
  for (int32_t r : raw.region) used[static_cast<std::size_t>(r)] = 0;
  std::vector<std::string> kept;
  for (std::size_t r = 0; r < used.size(); ++r)
    if (used[r] == 0) used[r] = static_cast<int32_t>(kept.size()), kept.push_back(raw.regions[r]);
  for (int32_t& r : raw.region) r = used[static_cast<std::size_t>(r)];
  raw.regions = std::move(kept);
  return raw;
}

// --- VTK .vtu ----------------------------------------------------------------------------------------
void collect_message(vtkObject*, unsigned long, void* client, void* call) {
  auto* messages = static_cast<std::string*>(client);
  if (!call) return;
  std::string m = static_cast<const char*>(call);
  while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
  *messages += (messages->empty() ? "" : "; ") + m;
}

std::string vtk_kind(int type) {
  const char* name = vtkCellTypes::GetClassNameFromTypeId(type);
  std::string s = name ? name : "unknown";
  if (s.rfind("vtk", 0) == 0) s = s.substr(3);
  return s + " (VTK cell type " + std::to_string(type) + ")";
}

// A region value as text: integers without a decimal point ("1", not "1.0").
std::string value_text(double v) {
  char b[32];
  if (v == std::floor(v) && std::abs(v) < 1e15) std::snprintf(b, sizeof b, "%.0f", v);
  else std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

RawMesh read_vtu(const std::string& file, int dim, const Fail& fail) {
  std::string messages;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(collect_message);
  cb->SetClientData(&messages);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, cb);
  reader->AddObserver(vtkCommand::WarningEvent, cb);
  if (!reader->CanReadFile(file.c_str()))
    raise(fail, "not a VTK XML UnstructuredGrid file" + (messages.empty() ? "" : " (" + messages + ")"));
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !messages.empty() || grid == nullptr)
    raise(fail, "VTK cannot read it: " + (messages.empty() ? std::string("the reader failed") : messages));

  RawMesh raw;
  raw.source_label = "cell";
  const vtkIdType np = grid->GetNumberOfPoints(), nc = grid->GetNumberOfCells();
  raw.points.resize(static_cast<std::size_t>(np));
  for (vtkIdType p = 0; p < np; ++p) grid->GetPoint(p, raw.points[static_cast<std::size_t>(p)].data());

  // The region array: the first of these names the file has; one value per cell.
  vtkCellData* cd = grid->GetCellData();
  vtkAbstractArray* regions = nullptr;
  for (const char* name : {"region", "gmsh:physical", "CellEntityIds"})
    if (!regions && cd) regions = cd->GetAbstractArray(name);
  auto* numeric = vtkDataArray::SafeDownCast(regions);
  auto* strings = vtkStringArray::SafeDownCast(regions);
  if (regions) {
    const std::string name = regions->GetName() ? regions->GetName() : "";
    if (!numeric && !strings) raise(fail, "its cell array '" + name + "' holds neither numbers nor strings");
    if (regions->GetNumberOfComponents() != 1)
      raise(fail, "its cell array '" + name + "' has " + std::to_string(regions->GetNumberOfComponents()) +
                      " components; a region is one value per cell");
    if (regions->GetNumberOfTuples() != nc)
      raise(fail, "its cell array '" + name + "' has " + std::to_string(regions->GetNumberOfTuples()) +
                      " values for " + std::to_string(nc) + " cells");
  }
  // Numeric regions in the order of their values, named regions in the order they first appear.
  std::map<double, int32_t> by_value;
  std::map<std::string, int32_t> by_name;
  std::map<int, int> dimension_of;  // cell type -> its dimension
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < nc; ++c) {
    const int type = grid->GetCellType(c);
    auto d = dimension_of.find(type);
    if (d == dimension_of.end()) d = dimension_of.emplace(type, grid->GetCell(c)->GetCellDimension()).first;
    if (d->second < dim) continue;
    if (d->second > dim) raise(fail, "cell " + std::to_string(c) + " is a 3D " + vtk_kind(type) + "; a 2D scene needs a 2D mesh");
    const bool ok = dim == 2 ? type == VTK_TRIANGLE || type == VTK_QUAD : type == VTK_TETRA || type == VTK_HEXAHEDRON;
    if (!ok) raise(fail, "cell " + std::to_string(c) + " is a " + vtk_kind(type) + "; " + taken_kinds(dim));
    grid->GetCellPoints(c, ids);
    int32_t r = 0;
    if (numeric) {
      r = by_value.emplace(numeric->GetTuple1(c), 0).first->second;  // numbered below
    } else if (strings) {
      r = by_name.emplace(strings->GetValue(c), static_cast<int32_t>(by_name.size())).first->second;
    }
    std::vector<vtkIdType> pts(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
    for (vtkIdType p : pts)
      if (p < 0 || p >= np) raise(fail, "cell " + std::to_string(c) + " refers to point " + std::to_string(p) + ", which it does not define");
    raw.add(pts.begin(), pts.end(), r, static_cast<std::size_t>(c));
  }
  if (numeric) {
    int32_t k = 0;
    for (auto& [value, index] : by_value) index = k++, raw.regions.push_back(value_text(value));
    for (std::size_t e = 0; e < raw.region.size(); ++e)
      raw.region[e] = by_value.at(numeric->GetTuple1(static_cast<vtkIdType>(raw.source[e])));
  } else if (strings) {
    raw.regions.resize(by_name.size());
    for (const auto& [name, index] : by_name) raw.regions[static_cast<std::size_t>(index)] = name;
  } else if (!raw.region.empty()) {
    raw.regions = {""};
  }
  return raw;
}

}  // namespace

template <int Dim>
Mesh<Dim> read_mesh_file(const std::string& file, const std::string& key, double length_scale) {
  if (!std::isfinite(length_scale) || length_scale <= 0.0)
    throw std::invalid_argument("read_mesh_file: length_scale must be finite and > 0");
  const Fail fail = [&](const std::string& why) { throw SceneError(key, file + ": " + why); };
  check_regular_file(file, fail);
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  RawMesh raw;
  if (ext == ".msh") raw = read_msh(file, Dim, fail);
  else if (ext == ".vtu") raw = read_vtu(file, Dim, fail);
  else raise(fail, "unknown mesh file extension '" + ext + "'; a mesh is read from a Gmsh .msh or VTK .vtu file");
  if (raw.region.empty()) raise(fail, no_elements(Dim));
  const auto to_metres = [length_scale](const Vec<3>& x) -> Vec<Dim> { return length_scale * x.head<Dim>(); };
  return detail::finish_mesh<Dim>(std::move(raw), to_metres, fail);
}

template Mesh<2> read_mesh_file<2>(const std::string&, const std::string&, double);
template Mesh<3> read_mesh_file<3>(const std::string&, const std::string&, double);

}  // namespace cleave::pem
