// An 8-bit RGB raster, the renderer's currency: what HeadlessContext captures, what write_png writes.
#pragma once

#include <cstdint>
#include <vector>

namespace cleave::viz {

// width x height pixels, top row first, 3 bytes (R, G, B) per pixel: rgb.size() == 3*width*height.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

}  // namespace cleave::viz
