// checkpoint.bin: a header naming the format, the method and the dimension, the run loop's
// counters, then the method's state (Method::save). Written beside and renamed, so a run killed
// while writing keeps the previous checkpoint whole.
#pragma once
#include <cstdint>
#include <filesystem>

#include "libmpm/method/method.hpp"

namespace cleave {

struct LoopCounters {
  uint64_t scene_hash = 0;
  int64_t next_frame = 0;  // index of the next frame of every series (64 bits: no padding in the file)
  double next_frame_time = 0.0, next_global_time = 0.0, next_tip_time = 0.0;
};

// Throws std::runtime_error naming the file and the cause ("No space left on device") and removes
// the temporary when the checkpoint cannot be written.
template <int Dim>
void write_checkpoint(const std::filesystem::path& file, const Method<Dim>& method, const LoopCounters& c);

// Loads the method's state and returns the counters. Throws RunRefused with the reason when the
// file is missing, not a checkpoint, of an earlier format, of another method, dimension or scene,
// or cut short: nothing the user can fix by running again, only by running without --resume.
template <int Dim>
LoopCounters read_checkpoint(const std::filesystem::path& file, Method<Dim>& method, uint64_t scene_hash);

}  // namespace cleave
