// The terrain's base color as every renderer of renders/ sees it: the baked ground (sRGB8, pixel
// centres, north at the top) looked up bilinearly by ENU (x, y), interpolated in sRGB as stored
// (as POV-Ray does) and decoded to linear; or one plain color without a bake. The Embree
// reference and the LDI view share it, so their ground can only differ by where they sample it.
#pragma once

#include <array>

#include "renders/trace/traced_shading.h"
#include "scene/ground_look.h"

namespace wangscape {

class GroundColors {
 public:
  // `bake` may be null (or empty): then every point is `plain`. The bake must outlive this.
  GroundColors(const GroundBake* bake, const Vec3f& plain);
  Vec3f at(double x, double y) const;

 private:
  const GroundBake* bake_;
  Vec3f plain_;
  std::array<float, 256> linear_{};
  double scale_x_ = 0, scale_y_ = 0;  // pixels per meter
};

}  // namespace wangscape
