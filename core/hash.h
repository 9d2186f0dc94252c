// The one integer mixer of the project: SplitMix64's output function (Steele et al. 2014), for
// deterministic, thread-independent draws keyed by positions, seeds and salts.
#pragma once

#include <cstdint>

namespace wangscape {

// A well-mixed 64-bit value of `z` (SplitMix64: the golden-ratio step, then its finalizer).
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// A uniform float in [0, 1) from the top 24 bits of a hash h (of mix64).
constexpr float unit_float(std::uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }

}  // namespace wangscape
