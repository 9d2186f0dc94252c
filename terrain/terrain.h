// A DEM placed in the scene's local east-north-up frame (see terrain/georef.h), with
// height, normal and slope at any ENU point.
//
// The DEM keeps its own grid (no resampling, so heights at its samples are the file's
// values). An ENU point is mapped to fractional DEM sample coordinates through a coarse
// lattice of exact conversions (ENU -> WGS 84 -> DEM CRS, every ~8 samples), bilinearly
// interpolated: the mapping is smooth, so this is exact to well under a millimeter, and a
// height lookup costs two bilinear interpolations.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "core/extent.h"
#include "terrain/dem.h"
#include "terrain/georef.h"

namespace wangscape {

struct TerrainOptions {
  std::optional<LatLon> origin;  // WGS 84 degrees; default: the DEM's center
};

// Ground height and the slope of the ground there.
struct GroundSample {
  double height = 0;                     // meters, orthometric
  double dz_dx = 0, dz_dy = 0;           // gradient, meters per meter
  std::array<double, 3> normal() const;  // unit, pointing up
  double slope_degrees() const;          // angle between the normal and up
};

class Terrain {
 public:
  // Reads the DEM (see read_dem) and sets up the ENU frame. Throws Error.
  static Terrain load(const std::filesystem::path& path, const TerrainOptions& options = {});
  Terrain(DemRaster dem, const TerrainOptions& options);

  const DemRaster& dem() const { return dem_; }
  const EnuFrame& frame() const { return frame_; }
  const CrsToWgs84& crs() const { return crs_; }
  // For manifests. The first call diagnoses the datum transformation (see CrsToWgs84::note).
  TerrainGeoreference georeference() const;

  // ENU bounding box of the DEM samples that have data, meters.
  Extent extent() const { return extent_; }
  // DEM sample spacing in meters along its columns and rows (at the DEM center).
  std::array<double, 2> spacing_m() const { return spacing_m_; }

  // --- Sampling. All thread-safe (const, no caches). Ground exists on DEM cells whose four
  // corners have data; elsewhere, and outside the DEM, these return nullopt.

  // Bilinear height at ENU (x, y), meters.
  std::optional<double> height(double x, double y) const {
    double u, v;
    if (!map_to_sample(x, y, u, v)) return std::nullopt;
    return height_at_sample(u, v);
  }
  // Height and gradient (of the bilinear surface) at ENU (x, y).
  std::optional<GroundSample> sample(double x, double y) const;
  std::optional<std::array<double, 3>> normal(double x, double y) const;
  std::optional<double> slope_degrees(double x, double y) const;

  // --- Coordinates.

  // Fractional DEM sample coordinates (col, row) of ENU (x, y) through the lattice; false
  // outside the lattice (which covers extent()).
  bool map_to_sample(double x, double y, double& col, double& row) const {
    LatticeHit hit;
    if (!locate_in_lattice(x, y, hit)) return false;
    col = hit.interpolate(&LatticeNode::col);
    row = hit.interpolate(&LatticeNode::row);
    return true;
  }
  // Bilinear height at fractional DEM sample coordinates; nullopt outside or on a cell
  // with a no-data corner.
  std::optional<double> height_at_sample(double col, double row) const {
    CellHit hit;
    if (!locate_in_dem(col, row, hit)) return std::nullopt;
    const double top = hit.p[0] + hit.tc * (hit.p[1] - hit.p[0]);
    const double bottom = hit.q[0] + hit.tc * (hit.q[1] - hit.q[0]);
    const double h = top + hit.tr * (bottom - top);
    if (std::isnan(h)) return std::nullopt;  // a no-data corner poisons the cell
    return h;
  }
  // Exact ENU x, y (meters) of DEM sample coordinates (col, row), in place, batched
  // (GDAL/OSR + GeographicLib, no lattice). Slow-ish (~1 us per point): for meshes, tests.
  void samples_to_enu(std::span<double> col_to_x, std::span<double> row_to_y) const;
  // Exact inverse: ENU x, y -> fractional DEM (col, row), in place, batched; NaN where
  // the point does not transform.
  void enu_to_samples(std::span<double> x_to_col, std::span<double> y_to_row) const;

 private:
  struct LatticeNode {
    double col, row;  // fractional DEM sample coordinates of the node
  };
  // A point inside a lattice cell: corners a[0], a[1] (south), b[0], b[1] (north).
  struct LatticeHit {
    const LatticeNode* a;
    const LatticeNode* b;
    double tx, ty;  // position in the cell, 0..1
    double interpolate(double LatticeNode::*field) const {
      const double south = a[0].*field + tx * (a[1].*field - a[0].*field);
      const double north = b[0].*field + tx * (b[1].*field - b[0].*field);
      return south + ty * (north - south);
    }
  };
  bool locate_in_lattice(double x, double y, LatticeHit& hit) const {
    const double fx = (x - lattice_x0_) * inverse_lattice_step_;
    const double fy = (y - lattice_y0_) * inverse_lattice_step_;
    if (!(fx >= 0 && fy >= 0 && fx <= lattice_max_fx_ && fy <= lattice_max_fy_)) return false;  // and NaN
    const int i = std::min(int(fx), lattice_nx_ - 2), j = std::min(int(fy), lattice_ny_ - 2);
    hit.a = &lattice_[std::size_t(j) * std::size_t(lattice_nx_) + std::size_t(i)];
    hit.b = hit.a + lattice_nx_;
    hit.tx = fx - i;
    hit.ty = fy - j;
    return true;
  }
  // A point inside a DEM cell: heights p[0], p[1] on row r, q[0], q[1] on row r + 1.
  struct CellHit {
    const float* p;
    const float* q;
    double tc, tr;  // position in the cell, 0..1
  };
  bool locate_in_dem(double col, double row, CellHit& hit) const {
    if (!(col >= 0 && row >= 0 && col <= max_col_ && row <= max_row_)) return false;
    const int c = std::min(int(col), dem_.width - 2), r = std::min(int(row), dem_.height - 2);
    hit.p = &dem_.heights[std::size_t(r) * std::size_t(dem_.width) + std::size_t(c)];
    hit.q = hit.p + dem_.width;
    hit.tc = col - c;
    hit.tr = row - r;
    return true;
  }
  void build_extent();
  void build_lattice();

  DemRaster dem_;
  CrsToWgs84 crs_;
  EnuFrame frame_;
  Extent extent_;
  std::array<double, 2> spacing_m_{0, 0};
  double max_col_ = 0, max_row_ = 0;

  std::vector<LatticeNode> lattice_;  // row-major from (lattice_x0_, lattice_y0_), south to north
  int lattice_nx_ = 0, lattice_ny_ = 0;
  double lattice_x0_ = 0, lattice_y0_ = 0, inverse_lattice_step_ = 1;
  double lattice_max_fx_ = 0, lattice_max_fy_ = 0;
};

}  // namespace wangscape
