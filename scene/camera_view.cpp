#include "scene/camera_view.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/vecmath.h"
#include "scene/scene.h"

namespace wangscape {

namespace {

using Vec3 = Vector3d;

constexpr double kDegree = std::numbers::pi / 180;

}  // namespace

double distance_for_pixels(double head_meters, double pixels, int width, double fov_degrees) {
  // One pixel at distance d covers 2 d tan(fov / 2) / width meters.
  return head_meters * width / (pixels * 2 * std::tan(fov_degrees * kDegree / 2));
}

CameraView::CameraView(const Camera& camera, const Sun& sun, double aspect, const CameraViewOptions& options)
    : options_(options), position_(camera.position) {
  const auto basis = camera_basis(camera.position, camera.target);  // make_camera refuses a camera looking straight up
  if (!basis) throw Error("camera-aware export: the camera looks straight up or down (no horizon to frame)");
  forward_ = basis->forward;
  right_ = basis->right;
  up_ = basis->up;
  const double half_x = camera.fov_degrees * kDegree / 2;
  tan_half_x_ = std::tan(half_x);
  tan_half_y_ = tan_half_x_ / std::max(aspect, 1e-6);
  const double half_y = std::atan(tan_half_y_);
  // Inward normals: a point p (from the camera) is inside where dot(p, n) >= 0 for all four.
  planes_[0] = std::sin(half_x) * forward_ - std::cos(half_x) * right_;  // right edge
  planes_[1] = std::sin(half_x) * forward_ + std::cos(half_x) * right_;  // left edge
  planes_[2] = std::sin(half_y) * forward_ - std::cos(half_y) * up_;     // top edge
  planes_[3] = std::sin(half_y) * forward_ + std::cos(half_y) * up_;     // bottom edge
  // A caster's shadow falls away from the sun and down: within sun_margin meters horizontally.
  const Vec3 to_sun = sun.direction();
  const double horizontal = std::hypot(to_sun[0], to_sun[1]);
  if (horizontal > 1e-9 && options.sun_margin > 0) {
    const double k = options.sun_margin / horizontal;
    shadow_sweep_ = {-k * to_sun[0], -k * to_sun[1], -k * to_sun[2]};
  }
}

double CameraView::distance(double x, double y, double z) const {
  return std::sqrt(dot(Vec3{x, y, z} - position_, Vec3{x, y, z} - position_));
}

bool CameraView::tile_visible(const Extent& tile, double z_min, double z_max) const {
  const double reach = options_.flower_reach;
  const double x0 = tile.min_x - reach, x1 = tile.max_x + reach, y0 = tile.min_y - reach, y1 = tile.max_y + reach;
  const double z0 = z_min, z1 = z_max + options_.flower_height;
  // Within far: the box's nearest point.
  const double dx = std::max({x0 - position_[0], 0.0, position_[0] - x1});
  const double dy = std::max({y0 - position_[1], 0.0, position_[1] - y1});
  const double dz = std::max({z0 - position_[2], 0.0, position_[2] - z1});
  if (dx * dx + dy * dy + dz * dz > options_.far * options_.far) return false;
  // The box and its shadow's box: outside when all 16 corners lie behind one side plane.
  std::array<Vec3, 16> corners;
  for (int k = 0; k < 8; ++k) {
    corners[static_cast<std::size_t>(k)] = Vec3{k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0} - position_;
    corners[static_cast<std::size_t>(k + 8)] = corners[static_cast<std::size_t>(k)] + shadow_sweep_;
  }
  for (const Vec3& n : planes_)
    if (std::all_of(corners.begin(), corners.end(), [&](const Vec3& c) { return dot(c, n) < 0; })) return false;
  return true;
}

std::array<double, 3> CameraView::far_view_direction() const {
  return normalized(Vec3{forward_[0], forward_[1], std::min(forward_[2], -0.05)});
}

Extent CameraView::window() const {
  // Rays over the frustum, `far` long, and the camera itself; the casters of shadows that fall
  // into them lie toward the sun, against the sweep.
  constexpr int kRays = 8;
  Extent box{position_[0], position_[1], position_[0], position_[1]};
  const auto add = [&](const Vec3& p) {
    box.min_x = std::min(box.min_x, p[0]);
    box.min_y = std::min(box.min_y, p[1]);
    box.max_x = std::max(box.max_x, p[0]);
    box.max_y = std::max(box.max_y, p[1]);
  };
  for (int a = 0; a <= kRays; ++a)
    for (int b = 0; b <= kRays; ++b) {
      const double sx = (2.0 * a / kRays - 1) * tan_half_x_, sy = (2.0 * b / kRays - 1) * tan_half_y_;
      const Vec3 ray = normalized(forward_ + sx * right_ + sy * up_);
      add(position_ + options_.far * ray);
    }
  add(position_ - shadow_sweep_);
  const Extent cone = box;
  add(Vec3{cone.min_x, cone.min_y, 0} - shadow_sweep_);
  add(Vec3{cone.max_x, cone.max_y, 0} - shadow_sweep_);
  // The far sphere bulges between the rays (under 1 % for 8 rays over 179 degrees): a margin.
  const double pad = 0.02 * options_.far + options_.flower_reach + options_.flower_height;
  return {box.min_x - pad, box.min_y - pad, box.max_x + pad, box.max_y + pad};
}

}  // namespace wangscape
