// What every scene exporter (POV-Ray, Blender arrays, glTF) receives: the assembled scene
// in ENU meters (x east, y north, z up). Exporters never re-run placement: instances come
// from a stream the pipeline provides.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "generator/instances.h"
#include "templates/mesh.h"

namespace wangscape {

struct Camera {
  std::array<double, 3> position{0, 0, 2};  // ENU meters
  std::array<double, 3> target{10, 0, 0};   // ENU meters
  double fov_degrees = 50.0;                // horizontal field of view
};

struct Sun {
  double azimuth_degrees = 135.0;   // clockwise from north (compass)
  double elevation_degrees = 35.0;  // above the horizon
  double strength = 1.0;            // relative intensity
  // Unit vector from the ground towards the sun, ENU.
  std::array<double, 3> direction() const;
};

struct RenderSettings {
  int width = 640;
  int height = 360;
  int antialias_samples = 1;  // POV-Ray +A depth / Cycles samples scale
  bool radiosity = false;     // POV-Ray radiosity switch
  int threads = 0;            // 0 = all cores
};

// Georeference carried into every manifest and header: ordered (key, value) strings, e.g.
// ("crs_wkt", ...), ("origin_latitude", "46.2"), ("units", "meters"), ("vertical_datum", ...).
using Georeference = std::vector<std::pair<std::string, std::string>>;

// Streams the scene's instances batch by batch; calls sink for each batch.
using InstanceStream = std::function<void(const std::function<void(const InstanceBatch&)>& sink)>;

struct Scene {
  std::string name = "wangscape";
  Mesh terrain;                      // ENU meters; may be empty (no terrain)
  std::vector<Mesh> models;          // one per variant; InstanceBatch::variant indexes this
  InstanceStream instances;          // may be empty (no instances)
  std::uint64_t instance_count = 0;  // exact count the stream will produce (for headers)
  Camera camera;
  Sun sun;
  RenderSettings render;
  Georeference georeference;
};

}  // namespace wangscape
