// Reading what `cleave run` writes: the particles.pvd index of a time series, one particles .vtu
// frame into memory, choosing frames from a user spec and picking one scalar per particle by name.
#pragma once
#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cleave::viz {

// One point-data array of a frame; values.size() == components * n_points, point-major.
struct PointArray {
  int components = 1;
  std::vector<double> values;
};

struct ParticleFrame {
  double time = 0;
  int dim = 2;                               // 3 unless every z == 0
  std::vector<std::array<double, 3>> x;      // particle positions (2D data: z = 0)
  std::map<std::string, PointArray> arrays;  // point data by name, converted to double
  std::string file;                          // where it was read from (empty if built in memory)
  std::size_t size() const { return x.size(); }
};

struct SeriesEntry {
  double time;
  std::filesystem::path file;  // absolute or relative to the working directory, ready to open
};

// `dir_or_pvd` is an output directory (reads DIR/particles.pvd) or a .pvd file. Entry files are
// resolved against the .pvd's directory; order is that of the .pvd (time order as written).
// Throws std::runtime_error naming the file when it is missing, unreadable or lists no frames.
std::vector<SeriesEntry> read_series(const std::filesystem::path& dir_or_pvd);

// Reads one particles .vtu (vtkXMLUnstructuredGridReader): positions and every point-data array
// (as double). dim = 3 unless every z == 0. Throws std::runtime_error naming the file on failure.
ParticleFrame read_particle_frame(const std::filesystem::path& vtu, double time);

// Frame selection spec: "all", "first", "last", "every:K" (K >= 1: indices 0, K, 2K, ...),
// "time:T" (the frame whose time is nearest T; the earlier one on a tie) or "index:I" (I < 0
// counts from the end, -1 = last). Returns ascending indices into `series`. Throws
// std::invalid_argument with a clear message for a bad spec or an index out of range, and for any
// spec but "all"/"every:K" when the series is empty.
std::vector<std::size_t> select_frames(const std::vector<SeriesEntry>& series,
                                       const std::string& spec);

// One scalar per particle, by name:
//   "sxx","syy","szz","sxy","syz","sxz"      stress components (array "stress", VTK order)
//   "exx","eyy","ezz","exy","eyz","exz"      strain components (array "strain", tensor shear)
//   "von_mises", "principal_stress_difference" (alias "s1-s2"): the array of that name, else
//                                            computed from "stress" (2D frames: in-plane s1 - s2)
//   "ux","uy","uz","|u|"                     displacement components / magnitude
//   "vx","vy","vz","|v|"                     velocity components / magnitude
//   "damage"                                 array "damage"
//   NAME, NAME:k, |NAME|                     any point array: a 1-component array as is, its
//                                            component k (0-based), or the Euclidean norm.
// Throws std::invalid_argument naming the request and listing what the frame offers when the
// field is missing (or a multi-component array is named without ":k").
std::vector<double> scalar_field(const ParticleFrame& frame, const std::string& name);

// The names scalar_field accepts for this frame (derived names first, then raw arrays).
std::vector<std::string> available_fields(const ParticleFrame& frame);

}  // namespace cleave::viz
