#include "viz/raster/series.hpp"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "libmpm/io/pvd_writer.hpp"

namespace fs = std::filesystem;

namespace cleave::viz {

namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

template <class T>
bool parse_number(const std::string& s, T& out) {
  const std::string t = trim(s);
  if (t.empty()) return false;
  const char* b = t.data();
  if constexpr (std::is_integral_v<T>) {
    if (*b == '+') ++b;
  }
  auto r = std::from_chars(b, t.data() + t.size(), out);
  return r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// Collects VTK error/warning messages of one object instead of printing them.
void collect_message(vtkObject*, unsigned long, void* client, void* call) {
  auto* msgs = static_cast<std::string*>(client);
  if (call) {
    std::string m = static_cast<const char*>(call);
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    if (!msgs->empty()) *msgs += "; ";
    *msgs += m;
  }
}

}  // namespace

std::vector<SeriesEntry> read_series(const fs::path& dir_or_pvd) {
  std::error_code ec;
  fs::path pvd = dir_or_pvd;
  if (fs::is_directory(pvd, ec)) pvd /= "particles.pvd";
  if (!fs::exists(pvd, ec))
    throw std::runtime_error("cannot read series " + pvd.string() + ": file does not exist");
  if (fs::is_directory(pvd, ec))
    throw std::runtime_error("cannot read series " + pvd.string() + ": is a directory");
  const auto index = io::PvdIndex::load(pvd);  // throws std::runtime_error naming the file
  if (index.entries().empty())
    throw std::runtime_error("cannot read series " + pvd.string() + ": it lists no frames");
  const fs::path base = pvd.parent_path();
  std::vector<SeriesEntry> out;
  out.reserve(index.entries().size());
  for (const auto& [t, name] : index.entries()) {
    fs::path f(name);
    out.push_back({t, f.is_absolute() ? f : base / f});
  }
  return out;
}

ParticleFrame read_particle_frame(const fs::path& vtu, double time) {
  auto fail = [&](const std::string& why) -> ParticleFrame {
    throw std::runtime_error("cannot read particle frame " + vtu.string() + ": " + why);
  };
  std::error_code ec;
  if (!fs::exists(vtu, ec)) return fail("file does not exist");
  if (!fs::is_regular_file(vtu, ec)) return fail("not a regular file");

  std::string messages;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(collect_message);
  cb->SetClientData(&messages);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, cb);
  reader->AddObserver(vtkCommand::WarningEvent, cb);
  const std::string name = vtu.string();
  if (!reader->CanReadFile(name.c_str()))
    return fail("not a VTK XML UnstructuredGrid file" + (messages.empty() ? "" : " (" + messages + ")"));
  reader->SetFileName(name.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !messages.empty() || grid == nullptr)
    return fail(messages.empty() ? "VTK reader failed" : messages);

  ParticleFrame f;
  f.time = time;
  f.file = name;
  const vtkIdType n = grid->GetNumberOfPoints();
  f.x.resize(static_cast<std::size_t>(n));
  bool planar = true;
  if (n > 0) {
    vtkPoints* pts = grid->GetPoints();
    if (pts == nullptr) return fail("points missing");
    for (vtkIdType i = 0; i < n; ++i) {
      double p[3];
      pts->GetPoint(i, p);
      f.x[static_cast<std::size_t>(i)] = {p[0], p[1], p[2]};
      if (p[2] != 0.0) planar = false;
    }
  }
  f.dim = planar ? 2 : 3;

  vtkPointData* pd = grid->GetPointData();
  const int na = pd ? pd->GetNumberOfArrays() : 0;
  for (int a = 0; a < na; ++a) {
    vtkDataArray* arr = pd->GetArray(a);  // null for non-numeric (string) arrays
    if (arr == nullptr || arr->GetName() == nullptr) continue;
    if (arr->GetNumberOfTuples() != n) return fail(std::string("array '") + arr->GetName() + "' has the wrong length");
    PointArray pa;
    pa.components = arr->GetNumberOfComponents();
    pa.values.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(pa.components));
    std::size_t k = 0;
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < pa.components; ++c) pa.values[k++] = arr->GetComponent(i, c);
    f.arrays[arr->GetName()] = std::move(pa);
  }
  return f;
}

std::vector<std::size_t> select_frames(const std::vector<SeriesEntry>& series,
                                       const std::string& spec_in) {
  const std::string spec = trim(spec_in);
  const std::size_t n = series.size();
  const std::string help =
      " (expected \"all\", \"first\", \"last\", \"every:K\", \"time:T\" or \"index:I\")";
  auto bad = [&](const std::string& why) -> std::vector<std::size_t> {
    throw std::invalid_argument("frame selection \"" + spec_in + "\": " + why + help);
  };
  auto need_frames = [&] {
    if (n == 0) bad("the series has no frames");
  };
  const auto colon = spec.find(':');
  const std::string key = trim(spec.substr(0, colon));
  const std::string arg = colon == std::string::npos ? std::string() : spec.substr(colon + 1);
  if (colon == std::string::npos) {
    if (key == "all") {
      std::vector<std::size_t> r(n);
      for (std::size_t i = 0; i < n; ++i) r[i] = i;
      return r;
    }
    if (key == "first") { need_frames(); return {0}; }
    if (key == "last") { need_frames(); return {n - 1}; }
    if (key == "every" || key == "time" || key == "index") return bad("\"" + key + "\" needs a value after ':'");
    return bad("unknown selection");
  }
  if (key == "every") {
    long long k = 0;
    if (!parse_number(arg, k) || k < 1) return bad("K must be an integer >= 1");
    std::vector<std::size_t> r;
    for (std::size_t i = 0; i < n; i += static_cast<std::size_t>(k)) r.push_back(i);
    return r;
  }
  if (key == "time") {
    double t = 0;
    if (!parse_number(arg, t) || !std::isfinite(t)) return bad("T must be a finite number");
    need_frames();
    std::size_t best = 0;
    double bd = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const double d = std::abs(series[i].time - t);
      if (d < bd) { bd = d; best = i; }
    }
    return {best};
  }
  if (key == "index") {
    long long i = 0;
    if (!parse_number(arg, i)) return bad("I must be an integer");
    need_frames();
    const long long sn = static_cast<long long>(n);
    const long long j = i < 0 ? sn + i : i;
    if (j < 0 || j >= sn)
      return bad("index " + std::to_string(i) + " is out of range; the series has " +
                 std::to_string(n) + " frame(s)");
    return {static_cast<std::size_t>(j)};
  }
  return bad("unknown selection \"" + key + "\"");
}

namespace {

const char* const kStressNames[6] = {"sxx", "syy", "szz", "sxy", "syz", "sxz"};
const char* const kStrainNames[6] = {"exx", "eyy", "ezz", "exy", "eyz", "exz"};

const PointArray* find_array(const ParticleFrame& f, const std::string& name) {
  auto it = f.arrays.find(name);
  return it == f.arrays.end() ? nullptr : &it->second;
}

std::vector<double> component(const ParticleFrame& f, const PointArray& a, int k) {
  const std::size_t n = f.x.size(), c = static_cast<std::size_t>(a.components);
  std::vector<double> r(n);
  for (std::size_t p = 0; p < n; ++p) r[p] = a.values[p * c + static_cast<std::size_t>(k)];
  return r;
}

std::vector<double> norm(const ParticleFrame& f, const PointArray& a) {
  const std::size_t n = f.x.size(), c = static_cast<std::size_t>(a.components);
  std::vector<double> r(n);
  for (std::size_t p = 0; p < n; ++p) {
    double s = 0;
    for (std::size_t i = 0; i < c; ++i) s += a.values[p * c + i] * a.values[p * c + i];
    r[p] = std::sqrt(s);
  }
  return r;
}

bool usable(const ParticleFrame& f, const PointArray* a, int min_components) {
  return a != nullptr && a->components >= min_components &&
         a->values.size() == f.x.size() * static_cast<std::size_t>(a->components);
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& e : v) s += (s.empty() ? "" : ", ") + e;
  return s.empty() ? "(nothing)" : s;
}

}  // namespace

std::vector<std::string> available_fields(const ParticleFrame& f) {
  std::vector<std::string> r;
  const PointArray* stress = find_array(f, "stress");
  const bool has_stress = usable(f, stress, 6);
  if (has_stress)
    for (const char* s : kStressNames) r.emplace_back(s);
  if (usable(f, find_array(f, "strain"), 6))
    for (const char* s : kStrainNames) r.emplace_back(s);
  if (has_stress || find_array(f, "von_mises")) r.emplace_back("von_mises");
  if (has_stress || find_array(f, "principal_stress_difference")) {
    r.emplace_back("principal_stress_difference");
    r.emplace_back("s1-s2");
  }
  if (usable(f, find_array(f, "displacement"), 3))
    for (const char* s : {"ux", "uy", "uz", "|u|"}) r.emplace_back(s);
  if (usable(f, find_array(f, "velocity"), 3))
    for (const char* s : {"vx", "vy", "vz", "|v|"}) r.emplace_back(s);
  for (const auto& [name, a] : f.arrays) {
    if (a.components == 1) r.push_back(name);
    else r.push_back(name + ":0.." + std::to_string(a.components - 1) + ", |" + name + "|");
  }
  return r;
}

std::vector<double> scalar_field(const ParticleFrame& f, const std::string& name_in) {
  const std::string name = trim(name_in);
  auto missing = [&](const std::string& why) -> std::vector<double> {
    throw std::invalid_argument("field \"" + name_in + "\": " + why + "; this frame" +
                                (f.file.empty() ? "" : " (" + f.file + ")") +
                                " offers: " + join(available_fields(f)));
  };
  auto need = [&](const char* array, int comps) -> const PointArray& {
    const PointArray* a = find_array(f, array);
    if (!a) missing(std::string("needs point array '") + array + "', which is missing");
    if (!usable(f, a, comps))
      missing(std::string("point array '") + array + "' has " + std::to_string(a->components) +
              " component(s) and " + std::to_string(a->values.size()) + " values for " +
              std::to_string(f.x.size()) + " particles");
    return *a;
  };

  for (int i = 0; i < 6; ++i) {
    if (name == kStressNames[i]) return component(f, need("stress", 6), i);
    if (name == kStrainNames[i]) return component(f, need("strain", 6), i);
  }
  static const char* const kVec[2][4] = {{"ux", "uy", "uz", "|u|"}, {"vx", "vy", "vz", "|v|"}};
  static const char* const kVecArray[2] = {"displacement", "velocity"};
  for (int v = 0; v < 2; ++v)
    for (int i = 0; i < 4; ++i)
      if (name == kVec[v][i]) {
        const PointArray& a = need(kVecArray[v], 3);
        return i < 3 ? component(f, a, i) : norm(f, a);
      }

  if (name == "von_mises") {
    if (const PointArray* a = find_array(f, "von_mises"); usable(f, a, 1) && a->components == 1)
      return a->values;
    const PointArray& s = need("stress", 6);
    std::vector<double> r(f.x.size());
    for (std::size_t p = 0; p < r.size(); ++p) {
      const double* t = &s.values[6 * p];
      const double a = t[0] - t[1], b = t[1] - t[2], c = t[2] - t[0];
      r[p] = std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
    }
    return r;
  }
  if (name == "principal_stress_difference" || name == "s1-s2") {
    const PointArray* a = find_array(f, "principal_stress_difference");
    if (usable(f, a, 1) && a->components == 1) return a->values;
    const PointArray& s = need("stress", 6);
    std::vector<double> r(f.x.size());
    for (std::size_t p = 0; p < r.size(); ++p) {
      const double* t = &s.values[6 * p];
      if (f.dim == 2) {
        r[p] = std::sqrt((t[0] - t[1]) * (t[0] - t[1]) + 4.0 * t[3] * t[3]);
      } else {
        Eigen::Matrix3d M;
        M << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
        const Eigen::Vector3d ev =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(M, Eigen::EigenvaluesOnly).eigenvalues();
        r[p] = ev[2] - ev[0];
      }
    }
    return r;
  }

  // A raw array, exactly as named.
  if (const PointArray* a = find_array(f, name)) {
    if (!usable(f, a, 1)) need(name.c_str(), 1);
    if (a->components == 1) return a->values;
    return missing("point array '" + name + "' has " + std::to_string(a->components) +
                   " components; ask for '" + name + ":k' (k = 0.." +
                   std::to_string(a->components - 1) + ") or '|" + name + "|'");
  }
  // |NAME|: Euclidean norm of an array's components.
  if (name.size() > 2 && name.front() == '|' && name.back() == '|') {
    const std::string an = name.substr(1, name.size() - 2);
    if (find_array(f, an)) return norm(f, need(an.c_str(), 1));
  }
  // NAME:k
  if (const auto c = name.rfind(':'); c != std::string::npos) {
    const std::string an = name.substr(0, c);
    if (find_array(f, an)) {
      const PointArray& a = need(an.c_str(), 1);
      long long k = -1;
      if (!parse_number(name.substr(c + 1), k) || k < 0 || k >= a.components)
        return missing("component must be an integer in 0.." + std::to_string(a.components - 1));
      return component(f, a, static_cast<int>(k));
    }
  }
  if (name == "damage") return missing("needs point array 'damage', which is missing");
  return missing("no such field");
}

}  // namespace cleave::viz
