#include "renders/trace/ground_colors.h"

#include <algorithm>
#include <cmath>

#include "core/color.h"

namespace wangscape {

GroundColors::GroundColors(const GroundBake* bake, const Vec3f& plain) : bake_(bake), plain_(plain) {
  for (int i = 0; i < 256; ++i) linear_[std::size_t(i)] = srgb8_to_linear(std::uint8_t(i));
  if (bake_ && (bake_->image.width < 1 || bake_->image.height < 1 || !(bake_->extent.width() > 0) ||
                !(bake_->extent.height() > 0)))
    bake_ = nullptr;
  if (bake_) {
    scale_x_ = double(bake_->image.width) / bake_->extent.width();
    scale_y_ = double(bake_->image.height) / bake_->extent.height();
  }
}

Vec3f GroundColors::at(double x, double y) const {
  if (!bake_) return plain_;
  const ImageRgb8& img = bake_->image;
  const Extent& e = bake_->extent;
  const double fx = std::clamp((x - e.min_x) * scale_x_ - 0.5, 0.0, double(img.width - 1));
  const double fy = std::clamp((e.max_y - y) * scale_y_ - 0.5, 0.0, double(img.height - 1));
  const int x0 = int(fx), y0 = int(fy);
  const int x1 = std::min(x0 + 1, img.width - 1), y1 = std::min(y0 + 1, img.height - 1);
  const float ax = float(fx - x0), ay = float(fy - y0);
  const std::uint8_t* p00 = img.pixels.data() + img.offset(x0, y0);
  const std::uint8_t* p10 = img.pixels.data() + img.offset(x1, y0);
  const std::uint8_t* p01 = img.pixels.data() + img.offset(x0, y1);
  const std::uint8_t* p11 = img.pixels.data() + img.offset(x1, y1);
  Vec3f out{};
  for (std::size_t c = 0; c < 3; ++c) {
    const float top = float(p00[c]) + (float(p10[c]) - float(p00[c])) * ax;
    const float bottom = float(p01[c]) + (float(p11[c]) - float(p01[c])) * ax;
    const float srgb = top + (bottom - top) * ay;  // 0..255
    const int i = std::clamp(int(srgb), 0, 254);
    out[c] = linear_[std::size_t(i)] + (linear_[std::size_t(i) + 1] - linear_[std::size_t(i)]) * (srgb - float(i));
  }
  return out;
}

}  // namespace wangscape
