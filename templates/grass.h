// Procedural grass clumps for meadows (Shade 2002's meadow of grass, dandelions and yellow
// flowers): many thin blades rising from a small tuft, arching out, fresh green to straw. Each
// is a Mesh in model space (meters, z up, the tuft's centre on the ground at the origin).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// Material slots of every grass mesh.
enum GrassMaterial : std::uint16_t { grass_blade = 0, grass_dry = 1, grass_straw = 2 };

// The three grass materials, in GrassMaterial order (linear RGB): green, yellowed, straw.
std::vector<Material> grass_materials();

// A clump needs a few blades of two triangles; above the maximum every blade has its full rows.
inline constexpr std::size_t kGrassMinimumTriangleBudget = 24;
inline constexpr std::size_t kGrassMaximumTriangleBudget = 9600;
inline constexpr std::size_t kGrassDefaultTriangleBudget = 600;

// One clump: variant `variant` (0-based) of the family drawn from `seed`, with at most
// `triangle_budget` triangles and no fewer than the budget less one blade (at most 24). The
// blade count and each blade's rows follow the budget; blade k has the same shape at every
// budget. Throws Error for a budget outside [minimum, maximum]. Pure: thread safe.
PlantModel make_grass_clump(std::uint64_t seed, int variant, std::size_t triangle_budget);

}  // namespace wangscape
