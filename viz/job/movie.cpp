#include "viz/job/movie.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cleave::viz {
namespace fs = std::filesystem;

fs::path encode_movie(const std::vector<fs::path>& frames, const fs::path& image_dir, const fs::path& movie_arg,
                      int fps) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    throw std::runtime_error("--movie needs Debian's ffmpeg (apt-get install ffmpeg; the README's set-up command installs it)");
  fs::path movie = movie_arg;
  if (movie.is_relative() && movie.parent_path().empty()) movie = image_dir / movie;
  const fs::path links = image_dir / (".movie_frames_" + std::to_string(getpid()));
  fs::remove_all(links);
  fs::create_directories(links);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "%06zu.png", k);
    fs::create_symlink(fs::absolute(frames[k]), links / name);
  }
  std::ostringstream cmd;
  cmd << "ffmpeg -loglevel error -y -framerate " << fps << " -i '" << (links / "%06d.png").string()
      << "' -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p '" << movie.string() << "'";
  const int rc = std::system(cmd.str().c_str());
  std::error_code ec;
  fs::remove_all(links, ec);
  if (rc != 0) throw std::runtime_error("ffmpeg failed to encode " + movie.string());
  return movie;
}

}  // namespace cleave::viz
