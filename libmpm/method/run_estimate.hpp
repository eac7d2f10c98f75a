// What a built scene's run will take: points, memory (the builder's estimate, RunSettings), and
// output (frames x bytes per frame + the CSV tables + the checkpoint, which is rewritten beside
// itself at every frame). `cleave check` prints it; `cleave run` refuses, before it writes anything,
// a run whose output would not fit on the output folder's disk, unless --force (a frame every step
// once wrote 2.4 GB in a minute without a word).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "libmpm/method/method.hpp"

namespace cleave {

struct RunEstimate {
  double points = 0, steps = 0, frames = 0;
  double memory_bytes = 0;      // the builder's estimate (RunSettings::memory_bytes)
  // One frame of every series: the XML, the cell arrays and the field bytes below, each array's
  // appended block as io/appended_blocks.hpp lays it out. Raw: the file's size, up to the XML's
  // length (allowed for generously). zlib: an upper bound (each block at zlib's compressBound, its
  // size on data that does not compress); the real size depends on the data.
  double frame_bytes = 0;
  // Of frame_bytes, the point coordinates and point data before any compression: 8 bytes a value,
  // or exactly half that with output.precision "float32".
  double field_bytes = 0;
  double table_bytes = 0;       // global.csv and crack_tips.csv at the end
  double checkpoint_bytes = 0;  // checkpoint.bin (twice that while it is rewritten)
  bool zlib = false, float32 = false;  // output.compression "zlib", output.precision "float32"
  std::string output_key;       // the scene key of the largest share of the output
  double output_bytes() const { return frames * frame_bytes + table_bytes + 2 * checkpoint_bytes; }
};

// Computes the estimate from the built method at its start (its frames at t = 0, its state).
template <int Dim>
RunEstimate estimate_run(Method<Dim>& method);

// Lines for `cleave check`: the estimate, the frames' encoding and the machine's figures (free disk
// in `out`).
std::vector<std::string> describe_estimate(const RunEstimate& e, const std::filesystem::path& out);

// The line of describe_estimate that names the frames' encoding: "output encoding: raw, float64
// (output.compression "none", output.precision "float64")"; with float32 the field bytes of a frame
// (half of float64's), with zlib that the output figure is an upper bound.
std::string describe_encoding(const RunEstimate& e);

// SceneError at e.output_key when the output would exceed the free disk of `out` (counting the
// files of an earlier run there, which a fresh run replaces), unless --force (core/resources.hpp).
void check_disk(const RunEstimate& e, const std::filesystem::path& out);

}  // namespace cleave
