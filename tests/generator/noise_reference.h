// Reference value-gradient noise for the noise tile tests, written independently of the kernel
// (generator/noise_tiles.h), and an untiled lattice: noise of the same kind with no tiles.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>

#include "generator/noise_tiles.h"

namespace wangscape::testing {

// A lattice point's {gx, gy, value} at integer lattice coordinates (px, py).
using LatticePointAt = std::function<std::array<float, 3>(std::int64_t, std::int64_t)>;

// Each lattice corner's ramp v + g . (p - c) weighted by fade(1 - |dx|) fade(1 - |dy|), at
// lattice coordinates (gx, gy); scaled to +-1 as the kernel documents.
inline double reference_noise(double gx, double gy, const LatticePointAt& point) {
  const auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const double cx = std::floor(gx), cy = std::floor(gy);
  double sum = 0;
  for (int dy = 0; dy <= 1; ++dy)
    for (int dx = 0; dx <= 1; ++dx) {
      const double ox = gx - (cx + dx), oy = gy - (cy + dy);
      const std::array<float, 3> g = point(static_cast<std::int64_t>(cx) + dx, static_cast<std::int64_t>(cy) + dy);
      sum += (g[2] + g[0] * ox + g[1] * oy) * fade(1 - std::abs(ox)) * fade(1 - std::abs(oy));
    }
  return sum / (std::sqrt(0.5) + NoiseTileSet::kPointValue);
}

// Untiled noise of the tiles' kind: every point's gradient (one of the kernel's 256 directions)
// and value (uniform in +-kPointValue) drawn from (px, py, seed, stream) alone.
inline LatticePointAt untiled_lattice(std::uint64_t seed, std::uint32_t stream = 0) {
  return [seed, stream](std::int64_t px, std::int64_t py) {
    const auto draw = [&](std::uint32_t salt) {
      std::seed_seq s{static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py),
                      static_cast<std::uint32_t>(seed) + salt};
      std::array<std::uint32_t, 1> out{};
      s.generate(out.begin(), out.end());
      return out[0];
    };
    const double angle = 2 * std::numbers::pi * ((draw(2 * stream) & 255) + 0.5) / 256.0;
    const double unit = draw(2 * stream + 1) / 4294967296.0;
    return std::array<float, 3>{static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)),
                                static_cast<float>(NoiseTileSet::kPointValue * (2 * unit - 1))};
  };
}

}  // namespace wangscape::testing
