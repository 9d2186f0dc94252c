#include "templates/mesh.h"

#include <algorithm>
#include <cmath>

#include "core/color.h"

namespace wangscape {

MeshExtent measure_extent(const Mesh& mesh) {
  MeshExtent extent;
  if (mesh.positions.empty()) return extent;
  extent.min = extent.max = mesh.positions.front();
  float radius_squared = 0;
  for (const auto& p : mesh.positions) {
    for (int axis = 0; axis < 3; ++axis) {
      extent.min[axis] = std::min(extent.min[axis], p[axis]);
      extent.max[axis] = std::max(extent.max[axis], p[axis]);
    }
    radius_squared = std::max(radius_squared, p[0] * p[0] + p[1] * p[1]);
  }
  extent.height = extent.max[2];
  extent.radius = std::sqrt(radius_squared);
  return extent;
}

std::array<float, 4> TextureImage::at(float u, float v) const {
  if (width <= 0 || height <= 0 || rgba.size() < std::size_t(width) * std::size_t(height) * 4) return {1, 1, 1, 1};
  const auto wrap = [](float t, int size) {
    const float repeated = std::isfinite(t) ? t - std::floor(t) : 0.0f;
    return std::min(size - 1, int(repeated * float(size)));
  };
  const int column = wrap(u, width), row = height - 1 - wrap(v, height);
  const std::uint8_t* texel = &rgba[(std::size_t(row) * std::size_t(width) + std::size_t(column)) * 4];
  return {srgb8_to_linear(texel[0]), srgb8_to_linear(texel[1]), srgb8_to_linear(texel[2]), float(texel[3]) / 255.0f};
}

void compute_vertex_normals(Mesh& mesh) {
  // Accumulate in double: large flat models sum thousands of tiny cross products per vertex.
  std::vector<std::array<double, 3>> sums(mesh.positions.size(), {0.0, 0.0, 0.0});
  for (const auto& tri : mesh.triangles) {
    const auto& a = mesh.positions[tri[0]];
    const auto& b = mesh.positions[tri[1]];
    const auto& c = mesh.positions[tri[2]];
    const double e1[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double e2[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    // The cross product's length is twice the area: this weights by area.
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (std::uint32_t v : tri) {
      for (int axis = 0; axis < 3; ++axis) sums[v][axis] += n[axis];
    }
  }
  mesh.normals.resize(mesh.positions.size());
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const auto& s = sums[i];
    const double length = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if (length > 0) {
      mesh.normals[i] = {float(s[0] / length), float(s[1] / length), float(s[2] / length)};
    } else {
      mesh.normals[i] = {0.0f, 0.0f, 1.0f};
    }
  }
}

}  // namespace wangscape
