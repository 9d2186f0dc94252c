// Quality figures of a 2-D point set (Cohen 2003, section 3.3; the issue-3 goals): minimum and
// nearest-neighbour distances over the hexagonal spacing, pairs closer than the packing
// diameter, density near tile edges and corners relative to tile interiors, and the radially
// averaged power spectrum with its anisotropy. Measured over whole tilings, across tile borders.
// Units: whatever the coordinates use (meters for placed instances, tile sides for tile sets).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "generator/ground_concept.h"
#include "generator/image.h"

namespace wangscape {

struct NeighbourStats {
  std::size_t counted = 0;  // points whose nearest neighbour is certainly inside the area
  double min_distance = 0;  // over all points
  double mean = 0, std = 0;
  double spread = 0;  // std / mean: 0 for a lattice
};

// Nearest-neighbour distances with a uniform grid. Points whose nearest neighbour could lie
// outside `area` (closer to its border than to any neighbour) are left out of mean and std.
NeighbourStats nearest_neighbour_stats(std::span<const float> x, std::span<const float> y, const Extent& area);

// Number of pairs closer than `diameter`, by more than the float rounding of coordinates of the
// area's magnitude (2^-21 of it: a few ulps), so pairs exactly at the diameter do not count.
std::size_t count_close_pairs(std::span<const float> x, std::span<const float> y, const Extent& area, double diameter);

struct RadialSpectrum {
  double window = 0;          // side of the square windows whose periodograms are averaged
  int windows = 0;            // how many were averaged
  double peak_frequency = 0;  // 1 / hexagonal spacing, cycles per unit
  // Per annulus k = 1..K (frequency k / window): mean power (1 = white noise) and anisotropy,
  // 10 log10(variance / mean^2) of the power in the annulus.
  std::vector<double> frequency, power, anisotropy_db;
  double noise_floor_db = 0;      // anisotropy of averaged white-noise periodograms: -10 log10(windows)
  double mean_anisotropy_db = 0;  // mean over annuli between 0.5 and 3 peak frequencies
  // The same without the frequencies of the tile grid (multiples of 1 / grid_period in both
  // axes), where tilings of a few tiles have spikes (Cohen 2003, Fig. 10b): the anisotropy of
  // the point process itself.
  double mean_anisotropy_off_grid_db = 0;
  // The averaged periodogram over the full frequency plane, image_size x image_size, row 0 =
  // highest positive ky, DC at the centre.
  int image_size = 0;
  std::vector<float> image;
};

// Averages periodograms of up to `max_windows` square windows of side `window` laid over `area`
// (row by row from its south-west corner), frequencies up to 3.5 / spacing. grid_period: the
// tile size, whose grid frequencies mean_anisotropy_off_grid_db leaves out (0: none).
RadialSpectrum radial_power_spectrum(std::span<const float> x, std::span<const float> y, const Extent& area,
                                     double window, int max_windows, double grid_period = 0);

struct PointMetricsOptions {
  Extent area;                  // what the points cover
  double tile_size = 1;         // tiles are [i s, (i+1) s) x [j s, (j+1) s)
  double packing_diameter = 0;  // pairs closer than this are violations
  double zone_width = 0;        // width of the edge and corner zones; 0 = packing_diameter
  bool spectrum = true;
  int spectrum_window_tiles = 8;
  int spectrum_windows = 16;
};

struct PointMetrics {
  std::size_t count = 0;
  double area = 0;
  double spacing = 0;  // hexagonal spacing sqrt(2 A / (sqrt(3) N))
  double min_distance = 0;
  double rho = 0;               // min_distance / spacing
  double mean_nn = 0;           // mean nearest-neighbour distance / spacing
  double nn_spread = 0;         // std / mean of nearest-neighbour distances
  std::size_t close_pairs = 0;  // pairs closer than the packing diameter
  // Density within zone_width of exactly one tile edge, and of two (a corner), over the density
  // of the tile interiors (complete tiles inside the area only).
  double edge_density_ratio = 0, corner_density_ratio = 0;
  RadialSpectrum spectrum;
};

PointMetrics measure_points(std::span<const float> x, std::span<const float> y, const PointMetricsOptions& options);

// Peak bytes per point of collecting the points (two floats) and measuring them (the grid's
// cell index, order and start, the spectrum windows' members), for estimating before a run.
inline constexpr double kMetricsBytesPerPoint = 8.0 + 4.0 + 4.0 + 8.0 + 4.0;

// A picture of the spectrum: left, the averaged periodogram (log scale, DC at the centre);
// right, the radial power (white: 1 = white noise level, blue: power) and the anisotropy (red,
// with its noise floor dashed) against frequency, up to 3.5 peak frequencies.
ImageRgb8 draw_spectrum_plot(const RadialSpectrum& spectrum, int height = 256);

}  // namespace wangscape
