// Measures of visible structure in a picture (issue 23): what a person sees as "the grid shows"
// in a tiled preview, as numbers a test can bound.
//
// - axis_energy_ratio: power-spectrum energy along the two image axes over that along the two
//   diagonals at the same frequencies. Straight axis-aligned lines, creases and grid-aligned
//   blocks put energy on the axes; isotropic texture gives about 1.
// - tile_repetition: how much of a preview repeats at a shift of whole tiles (the correlation of
//   the picture with itself shifted by one tile, the largest over the four directions); 0 for a
//   texture that never repeats, 1 for one tile repeated. tile_period_peak: the same, less what
//   the picture correlates at shifts a little shorter and longer than a tile.
//
// Images are grey values (any scale), row-major, top row first. Pure functions, thread-safe.
#pragma once

#include <span>
#include <vector>

#include "generator/image.h"

namespace wangscape {

struct GrayImage {
  int width = 0, height = 0;
  std::vector<float> values;  // row-major, top row first
  float at(int x, int y) const {
    return values[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

// Luma (Rec. 601 weights, 0..255) of an RGB image; the 16-bit values of a grey one.
GrayImage to_gray(const ImageRgb8& image);
GrayImage to_gray(const ImageGray16& image);

struct AxisEnergyOptions {
  // Frequencies counted, in cycles per pixel (0.5 = Nyquist): the annulus [lowest, highest].
  double lowest = 1.0 / 64, highest = 0.5;
  // Half-width of each wedge, degrees: energy within this angle of the axes (0, 90 degrees) over
  // the energy within it of the diagonals (45, 135 degrees).
  double wedge_degrees = 10;
};

// The axis-to-diagonal energy ratio of the image's power spectrum (the energy near the axes over
// that near the diagonals, both in the annulus [lowest, highest]), averaged over the whole
// squares of side n (the largest power of two <= the shorter side) that tile it from the top
// left (Welch), each with its mean removed and a radial Hann window applied (so neither the
// squares' own borders nor the window add axis energy).
// Throws Error when the image is smaller than 16 x 16.
double axis_energy_ratio(const GrayImage& image, const AxisEnergyOptions& options = {});

// Pearson correlation of the image with itself shifted by (dx, dy) pixels, over the overlap.
// 0 when the overlap is empty or flat.
double shifted_correlation(const GrayImage& image, int dx, int dy);

// The largest shifted_correlation over the shifts (p, 0), (0, p), (p, p), (p, -p), p = period.
double tile_repetition(const GrayImage& image, int period);

// The repetition that belongs to the tile grid: over the same four directions, the largest
// excess of the correlation at one tile's shift over the mean of those at 7/8 and 9/8 of it.
// Texture that is merely coherent over a tile (large patches, a smooth boundary between two
// exemplars) correlates alike at the three shifts and scores near 0; repeated tiles score up to 1.
double tile_period_peak(const GrayImage& image, int period);

}  // namespace wangscape
