// The pinhole projection of a Camera onto a frame of width x height pixels, as every drawing of
// the view uses it (the LDI renderer, the near field's and the sample cache's rays): the eye,
// its unit axes (ENU), the focal length in pixels per unit of tangent and the screen centre
// (pixel centres at +0.5; a sub-pixel shift moves the whole image). The same basis and pinhole
// as the Embree reference (renders/trace/embree_reference.h).
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/vecmath.h"
#include "scene/scene.h"

namespace wangscape {

struct ViewProjection {
  Vector3d eye{}, forward{}, right{}, up{};
  // Floats, as the rasterizers compute with them: tan of half the horizontal and vertical fields
  // of view, pixels per unit of tan, the screen centre (pixels).
  float tan_x = 1, tan_y = 1, focal = 1, cx = 0, cy = 0;

  // Throws Error for a field of view outside (0, 179] degrees or a camera with no direction.
  static ViewProjection of(const Camera& camera, int width, int height, std::array<float, 2> subpixel = {0, 0}) {
    check_field_of_view(camera.fov_degrees, "view: field of view");
    const auto basis = camera_basis(camera.position, camera.target);
    if (!basis)
      throw Error("view: the camera must look somewhere sideways (its target is straight above, below or at it)");
    ViewProjection p;
    p.eye = camera.position;
    p.forward = basis->forward;
    p.right = basis->right;
    p.up = basis->up;
    p.tan_x = float(std::tan(camera.fov_degrees * std::numbers::pi / 360));
    p.focal = float(width) / 2 / p.tan_x;
    p.tan_y = float(height) / 2 / p.focal;
    p.cx = float(width) / 2 + subpixel[0];
    p.cy = float(height) / 2 + subpixel[1];
    return p;
  }
  // An ENU point in camera space (right, up, forward), in floats as the rasterizers use it.
  std::array<float, 3> to_camera(double x, double y, double z) const {
    const Vector3d d{x - eye[0], y - eye[1], z - eye[2]};
    return {float(dot(d, right)), float(dot(d, up)), float(dot(d, forward))};
  }
  // True when all eight corners of the ENU box lie outside one plane of the frustum: nearer than
  // `near` meters, or beyond one side.
  bool box_outside_frustum(const Vector3d& low, const Vector3d& high, float near) const {
    int outside[5] = {0, 0, 0, 0, 0};
    for (int k = 0; k < 8; ++k) {
      const auto c = to_camera(k & 1 ? high[0] : low[0], k & 2 ? high[1] : low[1], k & 4 ? high[2] : low[2]);
      outside[0] += c[2] < near;
      outside[1] += c[0] > c[2] * tan_x;
      outside[2] += c[0] < -c[2] * tan_x;
      outside[3] += c[1] > c[2] * tan_y;
      outside[4] += c[1] < -c[2] * tan_y;
    }
    for (const int n : outside)
      if (n == 8) return true;
    return false;
  }
  // The unit direction (ENU) of the ray through the screen point (x, y).
  Vector3d ray_through(double x, double y) const {
    const double ray_right = (x - double(cx)) / double(focal), ray_up = -(y - double(cy)) / double(focal);
    Vector3d d;
    for (std::size_t c = 0; c < 3; ++c) d[c] = forward[c] + ray_right * right[c] + ray_up * up[c];
    return normalized(d);
  }
};

// The R2 low-discrepancy sequence's k-th sub-pixel offset, in [-0.5, 0.5) pixels; the first (k = 0)
// at the pixel centre.
inline std::array<float, 2> r2_offset(int k) {
  return {float(std::fmod(0.5 + k * 0.7548776662466927, 1.0) - 0.5),
          float(std::fmod(0.5 + k * 0.5698402909980532, 1.0) - 0.5)};
}

}  // namespace wangscape
