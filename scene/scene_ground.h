// The one ground a scene stands on, a DEM (terrain/) or a flat plane, with every mask of the
// scene file (min/max height, max slope, painted mask, georeferenced raster, polygons, the
// lat/lon area, fair edges). `wangscape build` and
// `wangscape scatter --dem` both place through it, so both accept every mask. It models
// generator's Ground concept (ENU meters, thread-safe).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/extent.h"
#include "generator/ground_concept.h"
#include "generator/placement.h"
#include "scene/scene_file.h"
#include "templates/mesh.h"
#include "terrain/terrain.h"

namespace wangscape {

class Terrain;

class SceneGround {
 public:
  // Loads the DEM of `terrain` (or makes a flat plane without one), crops it and builds the
  // masks, which are checked once here: a limit no ground can meet (a max_height below every
  // height of the DEM, a min_height above all of them, an all-black mask) is an Error naming it.
  // `area_latlon` ([tiles] area_latlon: [min_lat, min_lon, max_lat, max_lon], WGS 84 degrees) is a
  // mask too. A mask file that cannot be used is an Error naming the file, its key and what was
  // expected.
  static SceneGround load(const TerrainConfig& terrain, const MasksConfig& masks = {},
                          const std::optional<std::array<double, 4>>& area_latlon = {});

  // --- Ground concept (ENU meters; thread-safe).
  Extent extent() const;
  std::optional<double> height(double x, double y) const;
  std::optional<double> slope_degrees(double x, double y) const;
  // The ground's unit normal (pointing up) at ENU (x, y); +z on flat ground.
  std::optional<std::array<double, 3>> normal(double x, double y) const;
  // Height and gradient at ENU (x, y), whence the slope and normal above (one DEM read for both).
  std::optional<GroundSample> sample(double x, double y) const;

  // The ground height at ENU (x, y) (meters, orthometric as the DEM stores it). Throws Error
  // naming the ground and why it has none there: beyond its extent (given in the message), or a
  // DEM cell with a no-data corner.
  double height_or_error(double x, double y) const;

  // ENU x, y (meters) of a WGS 84 latitude/longitude (degrees).
  std::array<double, 2> to_enu(double latitude, double longitude) const;
  // The ENU box (meters) of a WGS 84 rectangle [min_lat, min_lon, max_lat, max_lon] (degrees).
  Extent lat_lon_box_extent(const std::array<double, 4>& box) const;
  // WGS 84 latitude, longitude (degrees) of the ENU origin.
  std::array<double, 2> origin() const;
  // The DEM, or nullptr for flat ground.
  const Terrain* terrain() const;

  // The ground as a mesh in ENU meters over extent(), a vertex per DEM sample (or every k-th,
  // to stay within `max_vertices`), with smooth normals.
  Mesh mesh(std::size_t max_vertices = 1'000'000) const;

  // Subdivides every triangle of `mesh` (this ground's mesh()) whose box meets `over` into
  // k x k triangles whose new vertices stand on the ground's bilinear surface, the one
  // placement sets flowers on: a plant a few centimetres tall sinks into a DEM cell's two flat
  // triangles otherwise (they stray from the bilinear surface by up to a quarter of the cell's
  // twist). Vertices on a shared edge are shared; a cell edge is straight on both surfaces, so
  // no crack opens against the triangles left as they were. k shrinks until the new triangles
  // stay within `max_new_triangles` (below 2: nothing is cut). Nothing happens on flat ground.
  void refine_mesh(Mesh& mesh, const Extent& over, int k, std::size_t max_new_triangles = 4'000'000) const;

  // Lays the filled tiles over the ground (placement.h) and streams the instances that pass
  // the masks: with fair edges, every tile that may pass is laid and each flower is kept only
  // if its own ground passes (the border follows the contour); without, only tiles whose whole
  // ground passes (Shade 2002, a staircase along the contour). Thread-safe.
  // `also` (optional) is asked first about every tile: a tile it refuses is never laid.
  // `point_rule` (optional) is asked about every point the masks keep, with its species and
  // rank (scene/species.h): a point it refuses is dropped.
  using PointRule = std::function<bool(double x, double y, double z, std::uint8_t species, float rank)>;
  PlacementStats place(const FilledTileSet& filled, const PlacementOptions& options,
                       const std::function<void(const InstanceBatch&)>& sink,
                       const std::function<bool(const TileCell&)>& also = {}, const PointRule& point_rule = {}) const;
  // Whether the masks let a flower grow at (x, y) on ground `z` high, in the tile `tile`
  // (the tile's whole ground is tested without fair edges, as place does).
  bool flowers_grow_at(double x, double y, double z, const Extent& tile) const;

  // Throws Error when tiles of `tile_size` meters cannot fit the ground; `what` names the value
  // in the message (a flag, a key).
  void check_tile_size(double tile_size, const std::string& what) const;
  // The share (0..1) of the ground where the masks let flowers grow, counted over the DEM's
  // cells and the mask's pixels (1 for flat ground): what scales a count of the extent's tiles
  // into an estimate of the placed ones.
  double growing_share() const;
  // Why a placement produced no instance, in one sentence (for an explained empty result).
  std::string explain_empty(double tile_size) const;

  // Ordered key/value strings for scene headers and manifests.
  std::vector<std::pair<std::string, std::string>> georeference() const;
  // Short description for messages, e.g. "SainteHelens.dem (327 x 468 samples, 30 m)".
  std::string description() const;

 private:
  template <class TileTest>
  PlacementStats place_by_rule(const FilledTileSet& filled, const PlacementOptions& options,
                               const std::function<void(const InstanceBatch&)>& sink, const TileTest& asked,
                               const PointRule& point_rule) const;
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};
static_assert(Ground<SceneGround>);

// "LAT,LON" in WGS 84 degrees (e.g. "46.2,-122.19"). Throws Error naming the text when it is
// not two finite numbers in range.
std::array<double, 2> parse_lat_lon(const std::string& text);

// "WIDTHxHEIGHT" (meters, east x north) as the plane [0, W] x [0, H]. Throws Error naming the
// text (as the --plane flag) when it is not two finite sizes > 0.
Extent parse_plane(const std::string& text);

}  // namespace wangscape
