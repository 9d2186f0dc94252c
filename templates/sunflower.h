// Procedural sunflowers: the eleven model variants the field is planted with (Cohen 2003, section 4;
// Shade 2002, section 6). Each is a Mesh in model space (meters, z up, stem base at the origin, head
// facing roughly +x before yaw) with four materials: petal, disk, stem, leaf.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

// Material slots of every sunflower mesh (index into Mesh::materials and Mesh::triangle_material).
enum SunflowerMaterial : std::uint16_t {
  sunflower_petal = 0,
  sunflower_disk = 1,
  sunflower_stem = 2,
  sunflower_leaf = 3
};

// The four sunflower materials, in SunflowerMaterial order (linear RGB).
std::vector<Material> sunflower_materials();

struct SunflowerOptions {
  int variant_count = 11;               // models to make, >= 1
  std::uint64_t seed = 1;               // same seed, same meshes (bit for bit)
  std::size_t triangle_budget = 35000;  // per model, see make_sunflower; met within a few triangles
};

// Below this a sunflower cannot keep every part (stem, leaves, head, two rings of petals).
inline constexpr std::size_t kSunflowerMinimumTriangleBudget = 400;
// Above this a budget is taken for a typo (each model would take hundreds of megabytes).
inline constexpr std::size_t kSunflowerMaximumTriangleBudget = 5'000'000;

struct SunflowerModel {
  Mesh mesh;
  MeshExtent extent;  // height (m, top of the head) and tight radius (m) for placement
  // meters, largest horizontal distance of the head (petals, disk) from the z axis: a packing
  // radius for heads that should not overlap, while leaves may.
  float crown_radius = 0;
  float head_diameter = 0;             // meters, petal tip to petal tip
  float disk_diameter = 0;             // meters, the brown seed disk
  std::array<float, 3> head_center{};  // meters, model space, center of the disk
  std::array<float, 3> head_facing{};  // unit vector the disk faces (roughly +x, drooping)
  int floret_count = 0;                // florets in the Vogel spiral
};

// One sunflower: variant `variant` (0-based) of the family drawn from `seed`, with at most
// `triangle_budget` triangles (and at least ~99% of it). Throws Error for a budget outside
// [kSunflowerMinimumTriangleBudget, kSunflowerMaximumTriangleBudget]. Thread-safe (pure function).
SunflowerModel make_sunflower(std::uint64_t seed, int variant, std::size_t triangle_budget);

// options.variant_count sunflowers, variants 0 .. count-1 of make_sunflower. Throws Error for a
// variant count below 1 or a budget make_sunflower rejects.
std::vector<SunflowerModel> make_sunflower_variants(const SunflowerOptions& options);

}  // namespace wangscape
