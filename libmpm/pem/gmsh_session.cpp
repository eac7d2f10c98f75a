#include "libmpm/pem/gmsh_session.hpp"

#include <gmsh.h>

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <clocale>
#include <cstdlib>
#include <exception>

namespace cleave::pem::detail {
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// Gmsh's element types PEM takes: first-order triangle (2), quadrangle (3), tetrahedron (4),
// hexahedron (5).
bool taken(int dim, int type) { return dim == 2 ? type == 2 || type == 3 : type == 4 || type == 5; }

}  // namespace

GmshSession::GmshSession() : lock_(gmsh_mutex()) {
  saved_.omp_threads = omp_get_max_threads();
  if (const char* l = std::setlocale(LC_NUMERIC, nullptr)) saved_.numeric_locale = l;
  rlimit stack{};
  if (getrlimit(RLIMIT_STACK, &stack) == 0) saved_.have_stack_limit = true, saved_.stack_soft = stack.rlim_cur;
  if (const char* p = std::getenv("PATH")) saved_.path = p;
  if (const char* p = std::getenv("PYTHONPATH")) saved_.python_path = p;
  try {
    gmsh::initialize(0, nullptr, false);
  } catch (...) {
    restore();
    throw;
  }
  try {
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 2);  // errors and warnings reach the log
    gmsh::option::setNumber("General.NumThreads", 1);
    for (const char* o : {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
      gmsh::option::setNumber(o, 1);
    gmsh::option::setNumber("Mesh.RandomSeed", 1);
    gmsh::logger::start();
  } catch (...) {
    gmsh::finalize();
    restore();
    throw;
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
  }
  restore();
}

void GmshSession::restore() const {
  omp_set_num_threads(saved_.omp_threads);
  if (!saved_.numeric_locale.empty()) std::setlocale(LC_NUMERIC, saved_.numeric_locale.c_str());
  rlimit stack{};
  if (saved_.have_stack_limit && getrlimit(RLIMIT_STACK, &stack) == 0 && stack.rlim_cur != saved_.stack_soft) {
    stack.rlim_cur = saved_.stack_soft;
    setrlimit(RLIMIT_STACK, &stack);
  }
  auto put = [](const char* name, const std::optional<std::string>& v) {
    if (v) setenv(name, v->c_str(), 1);
    else unsetenv(name);
  };
  put("PATH", saved_.path);
  put("PYTHONPATH", saved_.python_path);
}

std::string gmsh_failure() {
  std::string message;
  try {
    throw;
  } catch (const std::string& s) {
    message = s;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (const char* s) {
    message = s ? s : "";
  } catch (...) {
  }
  if (message.empty()) {
    try {
      gmsh::logger::getLastError(message);
    } catch (...) {
    }
  }
  return message.empty() ? std::string("Gmsh failed without a message") : message;
}

std::string gmsh_complaints() {
  std::vector<std::string> log, kept;
  try {
    gmsh::logger::get(log);
  } catch (...) {
    return "";
  }
  for (const std::string& line : log)
    if (line.rfind("Error", 0) == 0 || line.rfind("Warning", 0) == 0) kept.push_back(line);
  std::string s;
  for (std::size_t i = kept.size() > 3 ? kept.size() - 3 : 0; i < kept.size(); ++i) s += (s.empty() ? "" : " / ") + kept[i];
  return s.empty() ? s : "; Gmsh says: " + s;
}

RawMesh gmsh_elements(int dim, const std::vector<std::pair<int, int32_t>>& entity_regions, const Fail& fail) {
  RawMesh raw;
  raw.source_label = "Gmsh element";
  std::vector<std::size_t> tags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, false, false);
  // Points in the order of their Gmsh tags, so that the numbering is the same on every run.
  std::vector<std::size_t> order(tags.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tags[a] < tags[b]; });
  std::vector<std::size_t> sorted(tags.size());
  raw.points.resize(tags.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted[i] = tags[order[i]];
    raw.points[i] = Vec<3>(xyz[3 * order[i]], xyz[3 * order[i] + 1], xyz[3 * order[i] + 2]);
  }
  auto point_of = [&](std::size_t tag) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), tag);
    if (it == sorted.end() || *it != tag)
      raise(fail, "an element refers to node " + std::to_string(tag) + ", which the mesh does not define");
    return static_cast<int32_t>(it - sorted.begin());
  };

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  std::vector<int32_t> points;
  for (const auto& [entity, region] : entity_regions) {
    gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, entity);
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string name;
      int edim = 0, order = 0, count = 0, primary = 0;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(types[t], name, edim, order, count, local, primary);
      if (!taken(dim, types[t]))
        raise(fail, "it has elements of the kind Gmsh calls '" + name + "' (type " + std::to_string(types[t]) +
                        ", order " + std::to_string(order) + "); PEM takes first-order " +
                        (dim == 2 ? "triangles and quadrangles in 2D" : "tetrahedra and hexahedra in 3D"));
      const std::size_t n = static_cast<std::size_t>(count);
      for (std::size_t e = 0; e < element_tags[t].size(); ++e) {
        points.clear();
        for (std::size_t a = 0; a < n; ++a) points.push_back(point_of(node_tags[t][e * n + a]));
        raw.add(points.begin(), points.end(), region, element_tags[t][e]);
      }
    }
  }
  return raw;
}

}  // namespace cleave::pem::detail
