#include "libmpm/method/run_estimate.hpp"

#include <algorithm>
#include <streambuf>

#include "libmpm/core/error.hpp"
#include "libmpm/core/resources.hpp"
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

// Bytes of one frame file: coordinates, point arrays, cells (VTK_VERTEX: connectivity, offset and
// type per point; polylines: their ids), raw appended data, plus the XML around them.
double point_set_bytes(const io::PointSet& ps, bool float32) {
  const double value = float32 ? 4.0 : 8.0;
  double b = 4096.0 + double(ps.points.size()) * value;
  for (const auto& a : ps.arrays) b += double(a.values.size()) * value + 512.0;
  if (ps.polylines.empty()) return b + double(ps.size()) * 17.0;
  for (const auto& l : ps.polylines) b += double(l.size()) * 8.0 + 9.0;
  return b;
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
                      n == "crack_tips.csv" || n == "checkpoint.bin";
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
  for (std::size_t k = 0; k < series.size(); ++k) {
    const io::PointSet ps = method.frame(k);
    if (k == 0) e.points = double(ps.size());
    e.frame_bytes += point_set_bytes(ps, s.output.float32);
  }
  // CSV values print with 17 significant digits: about 22 bytes each; two tips per crack or tracker row.
  const double global = records_to_end(s, s.output.global_interval) * double(method.global_columns().size()) * 22.0;
  const auto tip_cols = method.tip_columns();
  const double tips = tip_cols.empty() ? 0.0 : records_to_end(s, s.output.tip_interval) * 2.0 * double(tip_cols.size()) * 22.0;
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
          format("estimate: about %s of output: %.0f frames x %s, tables %s, checkpoint %s (%s free in %s)",
                 format_bytes(e.output_bytes()).c_str(), e.frames, format_bytes(e.frame_bytes).c_str(),
                 format_bytes(e.table_bytes).c_str(), format_bytes(e.checkpoint_bytes).c_str(),
                 format_bytes(free_disk_bytes(out)).c_str(), out.string().c_str())};
}

void check_disk(const RunEstimate& e, const fs::path& out) {
  if (resource_checks_forced()) return;
  const double free = free_disk_bytes(out), earlier = earlier_output_bytes(out);
  if (e.output_bytes() > free + earlier)
    throw SceneError(e.output_key, "the run would write about " + format_bytes(e.output_bytes()) + " (" +
                                       format("%.0f", e.frames) + " frames x " + format_bytes(e.frame_bytes) +
                                       "), more than the " + format_bytes(free + earlier) + " free in " +
                                       out.string() + "; write fewer frames, fewer output.fields, or use "
                                       "--force to run anyway");
}

template RunEstimate estimate_run<2>(Method<2>&);
template RunEstimate estimate_run<3>(Method<3>&);

}  // namespace cleave
