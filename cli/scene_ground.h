// The ground a scene stands on, a DEM (terrain/) or a flat plane, behind one small value type.
// It keeps terrain/ headers out of the pipeline (terrain/georef.h and exporters/scene.h both
// declare a wangscape::Georeference) and satisfies generator's Ground concept.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/scene_config.h"
#include "generator/ground.h"
#include "generator/placement.h"
#include "templates/mesh.h"

namespace wangscape::cli {

class SceneGround {
 public:
  // Loads the DEM of `config` (or makes a flat plane without one) and crops it. Throws
  // Error naming the file, or Error when the crop misses the DEM.
  // `masks` are checked once here (a height threshold below every height of the DEM is an
  // error naming it).
  static SceneGround load(const TerrainConfig& config, const MasksConfig& masks = {});

  // --- Ground concept (ENU meters; thread-safe).
  Extent extent() const;
  std::optional<double> height(double x, double y) const;
  std::optional<double> slope_degrees(double x, double y) const;

  // ENU x, y (meters) of a WGS 84 latitude/longitude (degrees).
  std::array<double, 2> to_enu(double latitude, double longitude) const;
  // WGS 84 latitude, longitude (degrees) of the ENU origin.
  std::array<double, 2> origin() const;

  // The ground as a mesh in ENU meters over extent(), a vertex per DEM sample (or every k-th,
  // to stay within `max_vertices`), with smooth normals.
  Mesh mesh(std::size_t max_vertices = 1'000'000) const;

  // Lays the filled tiles over the ground (placement.h) and streams the instances that pass
  // the masks: with fair edges, every tile that may pass and then each point is tested;
  // without, only tiles whose whole ground passes (seed 003). Thread-safe.
  PlacementStats place(const FilledTileSet& filled, const PlacementOptions& options,
                       const std::function<void(const InstanceBatch&)>& sink) const;

  // Ordered key/value strings for scene headers and manifests.
  std::vector<std::pair<std::string, std::string>> georeference() const;
  // Short description for messages, e.g. "SainteHelens.dem (327 x 468, 30 m)".
  std::string description() const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};
static_assert(Ground<SceneGround>);

}  // namespace wangscape::cli
