// Triangle meshes with per-triangle materials: the form every model (procedural sunflower,
// user OBJ/PLY) takes before an exporter writes it. Model space: meters, z up, the model's
// ground contact point at the origin, +x the direction it faces before yaw.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace wangscape {

struct Material {
  std::string name;                   // e.g. "petal", "disk", "stem", "leaf"
  std::array<float, 3> base_color{};  // linear RGB, 0..1
  float roughness = 0.5f;             // 0 mirror .. 1 diffuse
  float translucency = 0.0f;          // 0..1, light passing through thin parts (petals, leaves)
};

struct Mesh {
  std::string name;
  std::vector<std::array<float, 3>> positions;          // meters
  std::vector<std::array<float, 3>> normals;            // unit, one per position
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<std::uint16_t> triangle_material;         // index into materials, one per triangle
  std::vector<Material> materials;

  std::size_t triangle_count() const { return triangles.size(); }
  std::size_t vertex_count() const { return positions.size(); }
};

}  // namespace wangscape
