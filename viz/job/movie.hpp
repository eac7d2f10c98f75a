// Encoding a movie from rendered frames with Debian's ffmpeg.
#pragma once
#include <filesystem>
#include <vector>

namespace cleave::viz {

// Encodes `frames` (PNG files of one size, in this order) as an H.264 MP4 at fps frames per second
// and returns its path: `movie`, in image_dir when it is a bare file name. The frames are named by
// their index in the series (every:K leaves gaps, and other renders may share the folder), so
// ffmpeg reads numbered links to exactly these files from a temporary folder, removed afterwards.
// Throws std::runtime_error when ffmpeg is missing or fails.
std::filesystem::path encode_movie(const std::vector<std::filesystem::path>& frames,
                                   const std::filesystem::path& image_dir, const std::filesystem::path& movie, int fps);

}  // namespace cleave::viz
