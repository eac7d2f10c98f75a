#include "libmpm/method/run_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <streambuf>

#include "libmpm/core/error.hpp"
#include "libmpm/core/resources.hpp"
#include "libmpm/io/appended_blocks.hpp"
#include "libmpm/method/describe.hpp"

namespace cleave {
namespace fs = std::filesystem;
namespace {

// A stream that counts what is written to it: the checkpoint's size without writing it.
class CountingBuf : public std::streambuf {
 public:
  double bytes = 0;

 protected:
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) ++bytes;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += double(n);
    return n;
  }
};

// Bytes of one DataArray's block of `raw` bytes in <AppendedData> (io/appended_blocks.hpp). Raw: a
// UInt64 count, then the bytes. zlib: 3 + (number of 32 KiB blocks) UInt64 words, then each block
// deflated, at most zlib's compressBound of it (n + n/4096 + n/16384 + n/2^25 + 13; the fractions
// here are not rounded down, so the sum bounds the real one).
double block_bytes(double raw, bool zlib) {
  if (!zlib) return 8.0 + raw;
  const double blocks = std::ceil(raw / double(io::kZlibBlockBytes));
  return 8.0 * (3.0 + blocks) + raw + raw / 4096.0 + raw / 16384.0 + raw / 33554432.0 + 13.0 * blocks;
}

struct FrameBytes {
  double total = 0, fields = 0;
};

// Bytes of one frame file as io/vtu_writer.cpp writes it: the XML (4 KiB and 512 bytes a DataArray:
// more than it takes), the points and point data (Float64 or Float32), and the cell arrays
// (connectivity and offsets Int64, types UInt8): a vertex per point, or a line per segment of each
// polyline (a one-point polyline: a vertex) and a triangle per triangle.
FrameBytes point_set_bytes(const io::PointSet& ps, bool float32, bool zlib) {
  const double value = float32 ? 4.0 : 8.0;
  FrameBytes f;
  f.total = 4096.0;
  auto array = [&](double raw) { f.total += 512.0 + block_bytes(raw, zlib); };
  f.fields = double(ps.points.size()) * value;
  array(double(ps.points.size()) * value);
  for (const auto& a : ps.arrays) {
    f.fields += double(a.values.size()) * value;
    array(double(a.values.size()) * value);
  }
  double ids = 0, cells = 0;
  if (ps.polylines.empty() && ps.triangles.empty()) {
    ids = cells = double(ps.size());
  } else {
    for (const auto& l : ps.polylines) {
      if (l.empty()) continue;  // no cell
      const double segments = l.size() == 1 ? 1.0 : double(l.size()) - 1.0;
      cells += segments;
      ids += l.size() == 1 ? 1.0 : 2.0 * segments;
    }
    cells += double(ps.triangles.size());
    ids += 3.0 * double(ps.triangles.size());
  }
  array(8.0 * ids);    // connectivity
  array(8.0 * cells);  // offsets
  array(cells);        // types
  return f;
}

// Bytes in `out` of the files a run writes there (a fresh run replaces them; a resumed one keeps
// them, and they are part of the estimate).
double earlier_output_bytes(const fs::path& out) {
  std::error_code ec;
  double b = 0;
  if (!fs::is_directory(out, ec)) return 0;
  for (const auto& e : fs::directory_iterator(out, ec)) {
    const std::string n = e.path().filename().string();
    const bool ours = e.path().extension() == ".vtu" || e.path().extension() == ".pvd" || n == "global.csv" ||
                      n == "crack_tips.csv" || n == "crack_fronts.csv" || n == "crack_growth.csv" || n == "checkpoint.bin";
    if (ours && e.is_regular_file(ec)) b += double(e.file_size(ec));
  }
  return b;
}

}  // namespace

template <int Dim>
RunEstimate estimate_run(Method<Dim>& method) {
  const RunSettings& s = method.settings();
  RunEstimate e;
  e.steps = steps_to_end(s);
  e.frames = records_to_end(s, s.output.interval);
  e.memory_bytes = s.memory_bytes;
  const auto series = method.frame_series();
  e.zlib = s.output.zlib;
  e.float32 = s.output.float32;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const io::PointSet ps = method.frame(k);
    if (k == 0) e.points = double(ps.size());
    const FrameBytes f = point_set_bytes(ps, e.float32, e.zlib);
    e.frame_bytes += f.total;
    e.field_bytes += f.fields;
  }
  // CSV values print with 17 significant digits: about 22 bytes each; the method says how many rows a record has.
  const double global = records_to_end(s, s.output.global_interval) * double(method.global_columns().size()) * 22.0;
  const auto tip_cols = method.tip_columns();
  const double tips = tip_cols.empty() ? 0.0 : records_to_end(s, s.output.tip_interval) * double(method.tip_rows_per_record()) *
                                                 double(tip_cols.size()) * 22.0;
  e.table_bytes = global + tips;
  CountingBuf counter;
  std::ostream counted(&counter);
  StateWriter w(counted);
  method.save(w);
  e.checkpoint_bytes = counter.bytes + 4096.0;
  const double frames = e.frames * e.frame_bytes, ck = 2 * e.checkpoint_bytes;
  e.output_key = frames >= std::max({global, tips, ck}) ? "output.interval"
                 : global >= std::max(tips, ck)         ? "output.global_interval"
                 : tips >= ck                           ? "output.tip_interval"
                                                        : s.size_key;
  return e;
}

std::vector<std::string> describe_estimate(const RunEstimate& e, const fs::path& out) {
  // Available before this process built the scene: what is available now plus what it holds.
  const double avail = available_memory_bytes() + resident_bytes();
  return {format("estimate: %.0f points, %.0f steps, about %s of memory (%s available)", e.points, e.steps,
                 format_bytes(e.memory_bytes).c_str(), format_bytes(avail).c_str()),
          describe_encoding(e),
          format("estimate: %s %s of output: %.0f frames x %s, tables %s, checkpoint %s (%s free in %s)",
                 e.zlib ? "at most" : "about", format_bytes(e.output_bytes()).c_str(), e.frames,
                 format_bytes(e.frame_bytes).c_str(), format_bytes(e.table_bytes).c_str(),
                 format_bytes(e.checkpoint_bytes).c_str(), format_bytes(free_disk_bytes(out)).c_str(),
                 out.string().c_str())};
}

std::string describe_encoding(const RunEstimate& e) {
  std::string line = std::string("output encoding: ") + (e.zlib ? "zlib" : "raw") + ", " +
                     (e.float32 ? "float32" : "float64") + " (output.compression \"" + (e.zlib ? "zlib" : "none") +
                     "\", output.precision \"" + (e.float32 ? "float32" : "float64") + "\")";
  if (e.float32) line += "; point coordinates and data " + format_bytes(e.field_bytes) + " a frame, half of float64's";
  if (e.zlib) line += "; the output figure is an upper bound: zlib's sizes depend on the data";
  return line;
}

void check_disk(const RunEstimate& e, const fs::path& out) {
  if (resource_checks_forced()) return;
  const double free = free_disk_bytes(out), earlier = earlier_output_bytes(out);
  if (e.output_bytes() > free + earlier)
    throw SceneError(e.output_key, std::string("the run would write ") + (e.zlib ? "at most " : "about ") +
                                       format_bytes(e.output_bytes()) + " (" +
                                       format("%.0f", e.frames) + " frames x " + format_bytes(e.frame_bytes) +
                                       "), more than the " + format_bytes(free + earlier) + " free in " +
                                       out.string() + "; write fewer frames, fewer output.fields, or use "
                                       "--force to run anyway");
}

template RunEstimate estimate_run<2>(Method<2>&);
template RunEstimate estimate_run<3>(Method<3>&);

}  // namespace cleave
