// Restart files: the full particle state plus counters, written beside each output frame so that a
// stopped run resumes from its last output (`cleave run --resume`).
#pragma once
#include <cstdint>
#include <filesystem>

#include "libmpm/model/model.hpp"

namespace cleave::io {

struct CheckpointInfo {
  uint64_t scene_hash = 0;
  double time = 0.0;
  long step = 0;
  double external_work = 0.0;
  int next_frame = 0;         // index of the next particle frame
  double next_frame_time = 0.0;
  double next_global_time = 0.0;
};

template <int Dim>
void write_checkpoint(const std::filesystem::path& file, const Model<Dim>& m, const CheckpointInfo& info);

// Restores particle state into m (built from the same scene); throws std::runtime_error naming the
// file when it is unreadable, truncated, of another dimension or particle count.
template <int Dim>
CheckpointInfo read_checkpoint(const std::filesystem::path& file, Model<Dim>& m);

}  // namespace cleave::io
