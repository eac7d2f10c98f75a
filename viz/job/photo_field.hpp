// A run's frame seen through a photograph's pixels (cleave compare --map, cleave fit --photo): the
// model's principal stress difference at every photo pixel, the simulated fringe centre-lines drawn
// over the photo, the fringe-order agreement of the two, and the scale (fringe constant or load)
// that makes the model's fringes fit the photo's.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "viz/fit/fringe_fit.hpp"
#include "viz/job/render_job.hpp"
#include "viz/optics/photoelastic.hpp"
#include "viz/render/image.hpp"

namespace cleave::viz {

// s1 - s2 (Pa) of a drawn 2D frame at each photo pixel centre (NaN where the pixel is off the
// bodies), the photo mapped by `map`.
struct PhotoField {
  int width = 0, height = 0;
  std::vector<double> diff;  // row-major, top row first
};
PhotoField photo_field(const ParticleFrame& f, int width, int height, const PhotoMap& map);

// Pixels to compare: on the bodies, inside `mask` where given (same size as the photo; a pixel
// counts where the mask is brighter than mid-grey), and inside the model-coordinate box `roi`.
std::vector<uint8_t> compared_pixels(const PhotoField& m, const PhotoMap& map, const Image* mask,
                                     const std::optional<std::array<double, 4>>& roi);

// The photo with the model's fringe centre-lines over it: integer orders in red, half orders in blue
// (which are dark and which light depends on the polariscope), each line one pixel wide, the orders
// of the integer lines written beside them. `scale` multiplies the model's stresses (a load scale).
Image centre_line_overlay(const Image& photo, const PhotoField& m, const PhotoelasticSettings& s, double scale = 1.0);

// Fringe-order agreement: the photo's intensity (normalised to its 1st..99th percentiles over the
// compared pixels) turned into a folded fringe order, the distance of N to the nearest integer in
// [0, 1/2] (dark field I = sin^2(pi N); light field the complement), against the model's folded order.
// Unlike the luminance correlation it does not flip sign between a dark- and a light-field photo
// compared with a model rendered in the other field.
struct FoldedOrderAgreement {
  double ncc = 0;  // correlation of the folded orders
  double rms = 0;  // RMS difference of the folded orders (fringes, at most 1/2)
  std::size_t pixels = 0;
};
FoldedOrderAgreement folded_order_agreement(const Image& photo, const PhotoField& m, const std::vector<uint8_t>& use,
                                            const PhotoelasticSettings& s, double scale = 1.0);

// The model's monochromatic intensity at scale c against the photo's luminance, correlated over the
// compared pixels and maximised over c (a log-spaced scan of 0.2..5 refined by golden section):
// the photo's fringe constant is f_sigma / c, or its load c times the run's.
struct PhotoCalibration {
  double scale = 1, ncc = 0, ncc_at_one = 0;
  std::size_t pixels = 0;
};
PhotoCalibration calibrate_to_photo(const Image& photo, const PhotoField& m, const std::vector<uint8_t>& use,
                                    const PhotoelasticSettings& s);

// Fringe centre-lines read from a photo as fringe-order points (model coordinates) for the fit: the
// darkest and brightest lines of the photo's normalised intensity (a pixel at most 0.25 / at least
// 0.75 that is a minimum / maximum across its row or its column), between r0 and r1 from the tip
// (x0, y0). The dark lines of a dark-field picture are whole orders, its bright lines half orders (the
// other way round in a light field); which whole or half order each is, the model tells: the nearest
// one to `scale` x the model's N there, kept only where the model is within 0.3 of it. At most
// `max_points`, evenly thinned.
std::vector<FringePoint> extract_fringe_points(const Image& photo, const PhotoField& m, const PhotoMap& map,
                                               const std::vector<uint8_t>& use, const PhotoelasticSettings& s, double scale,
                                               double x0, double y0, double r0, double r1, std::size_t max_points = 3000);

}  // namespace cleave::viz
