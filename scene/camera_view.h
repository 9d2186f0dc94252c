// Camera-aware export ([camera_aware], docs/scene-file.md): what a still's camera can see, as a
// test on tiles before any point is placed. A tile is laid when its box (ground heights plus
// the flowers' height and reach), swept away from the sun by the shadow margin, meets the
// camera's frustum within the far distance; the window is the rectangle holding every such
// tile, so placement costs what is visible, not what the DEM holds. Flowers closer than `near`
// are the full models, up to `far` the proxies; beyond `far` the ground bake carries the field
// (scene/far_field.h).
#pragma once

#include <array>
#include <cstdint>

#include "core/extent.h"

namespace wangscape {

struct Camera;
struct Sun;

// Where a flower head of `head_meters` spans `pixels` pixels of an image `width` pixels wide
// with a horizontal field of view of `fov_degrees`.
double distance_for_pixels(double head_meters, double pixels, int width, double fov_degrees);

struct CameraViewOptions {
  double near = 0, far = 0;   // meters from the camera
  double sun_margin = 0;      // meters (horizontal) toward the sun
  double flower_height = 2;   // meters above the ground, the tallest flower
  double flower_reach = 0.5;  // meters, how far a flower reaches beyond its point sideways
};

class CameraView {
 public:
  CameraView(const Camera& camera, const Sun& sun, double aspect, const CameraViewOptions& options);

  // Whether a tile with ground bounds `tile` and ground heights in [z_min, z_max] may show in
  // the still, itself or by its shadows, within the far distance.
  bool tile_visible(const Extent& tile, double z_min, double z_max) const;
  // The rectangle (ENU m) holding every tile tile_visible may accept.
  Extent window() const;
  // Meters from the camera to the point.
  double distance(double x, double y, double z) const;

  const CameraViewOptions& options() const { return options_; }
  const std::array<double, 3>& position() const { return position_; }
  // The unit direction the camera sees the far field along: its forward, looking down a little.
  std::array<double, 3> far_view_direction() const;

 private:
  CameraViewOptions options_;
  std::array<double, 3> position_{};
  std::array<std::array<double, 3>, 4> planes_{};  // inward normals of the four side planes
  std::array<double, 3> forward_{}, right_{}, up_{};
  double tan_half_x_ = 0, tan_half_y_ = 0;
  std::array<double, 3> shadow_sweep_{};  // a caster's shadow lies within this offset of it
};

}  // namespace wangscape
