// A procedural small yellow flower for meadows: a dandelion (Taraxacum), a rosette of toothed
// basal leaves, a bare hollow stem and one head of many yellow ligules (Shade 2002's meadow
// of grass, dandelions and yellow flowers). Model space: meters, z up, the rosette's centre on
// the ground at the origin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// Material slots of every wildflower mesh.
enum WildflowerMaterial : std::uint16_t { wildflower_petal = 0, wildflower_stem = 1, wildflower_leaf = 2 };

// The three wildflower materials, in WildflowerMaterial order (linear RGB).
std::vector<Material> wildflower_materials();

// Below the minimum a flower cannot keep every part (stem, leaves, head, its three rings of
// ligules at one triangle pair each).
inline constexpr std::size_t kWildflowerMinimumTriangleBudget = 300;
inline constexpr std::size_t kWildflowerMaximumTriangleBudget = 200'000;
inline constexpr std::size_t kWildflowerDefaultTriangleBudget = 1500;

// One flower: variant `variant` (0-based) of the family drawn from `seed`, with at most
// `triangle_budget` triangles (the finest tessellation of its parts that fits). Throws Error for a
// budget outside [minimum, maximum]. Pure: thread safe.
PlantModel make_wildflower(std::uint64_t seed, int variant, std::size_t triangle_budget);

}  // namespace wangscape
