// Triangle meshes with per-triangle materials: the form every model (procedural sunflower,
// a user's model read through Assimp) takes before an exporter writes it. Model space: meters, z up, the model's
// ground contact point at the origin, +x the direction it faces before yaw.
#pragma once

#include "core/error.h"

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace wangscape {

// An image a material maps over its triangles (through Mesh::uvs), decoded once on loading so
// that every engine sees the same texels: RGBA, 8 bits, the colour sRGB-encoded, alpha the
// coverage (a leaf card's cutout); row 0 is the image's top (v = 1).
struct TextureImage {
  std::string name;  // a file name for its copy in a scene folder, without extension ("leaf_card")
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4

  // The texel nearest (u, v), repeated outside [0, 1): linear RGB and alpha in [0, 1].
  std::array<float, 4> at(float u, float v) const;
};

struct Material {
  std::string name;                                      // e.g. "petal", "disk", "stem", "leaf"
  std::array<float, 3> base_color{};                     // linear RGB, 0..1; multiplies base_color_map's texels
  float roughness = 0.5f;                                // 0 mirror .. 1 diffuse
  float translucency = 0.0f;                             // 0..1, light passing through thin parts (petals, leaves)
  std::shared_ptr<const TextureImage> base_color_map{};  // null: base_color alone
  // > 0: a cutout (leaf cards): where base_color_map's alpha is below this there is no surface.
  float alpha_cutoff = 0.0f;
};

struct Mesh {
  std::string name;
  std::vector<std::array<float, 3>> positions;          // meters
  std::vector<std::array<float, 3>> normals;            // unit, one per position
  std::vector<std::array<float, 2>> uvs;                // one per position, or empty; v = 0 at the image's bottom
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<std::uint16_t> triangle_material;         // index into materials, one per triangle
  std::vector<Material> materials;

  std::size_t triangle_count() const { return triangles.size(); }
  std::size_t vertex_count() const { return positions.size(); }
};

// Extent of a model in model space, for placement.
struct MeshExtent {
  float height = 0;            // meters, highest z (the ground contact point is at z = 0)
  float radius = 0;            // meters, largest horizontal distance of any vertex from the z axis (tight radius)
  std::array<float, 3> min{};  // meters, axis-aligned box
  std::array<float, 3> max{};
};

// A generated model (grass clump, wildflower) and its extent: extent.radius is its tight radius.
struct PlantModel {
  Mesh mesh;
  MeshExtent extent;
};

// Measures the extent of every vertex; an empty mesh gives all zeros.
MeshExtent measure_extent(const Mesh& mesh);

// Replaces mesh.normals by smooth per-vertex normals: the area-weighted sum of the normals of the
// triangles using each vertex, normalized. Vertices that only touch degenerate triangles get +z.
void compute_vertex_normals(Mesh& mesh);

}  // namespace wangscape
