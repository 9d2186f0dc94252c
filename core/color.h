// Colours, in the manner of pbrt-v4's util/color.h: the one sRGB transfer (IEC 61966-2-1), both
// ways, in float. Pure functions: thread safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace wangscape {

// sRGB-encoded value in [0, 1] -> linear light.
inline float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// An 8-bit sRGB code (0..255) -> linear light in [0, 1].
inline float srgb8_to_linear(std::uint8_t v) { return srgb_to_linear(static_cast<float>(v) / 255.0f); }

// Linear light, clamped to [0, 1] -> sRGB-encoded value in [0, 1].
inline float linear_to_srgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// Linear light, clamped to [0, 1] -> the nearest 8-bit sRGB code.
inline std::uint8_t linear_to_srgb8(float v) {
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(v) * 255.0f));
}

}  // namespace wangscape
