// Small scenes for the Blender and glTF tests and benchmarks, built in C++ so they do not
// depend on the pipeline: a wavy terrain grid, three simple flower-like variants with two to
// four materials, and instances generated on the fly by the stream (none are stored).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "scene/scene.h"

namespace wangscape::testing {

// Terrain height (m) at (x, y) (m), and its gradient, for the test terrain.
inline float test_height(float x, float y) { return 0.8f * std::sin(0.2f * x) * std::cos(0.15f * y); }
inline std::array<float, 3> test_normal(float x, float y) {
  const float dx = 0.8f * 0.2f * std::cos(0.2f * x) * std::cos(0.15f * y);
  const float dy = -0.8f * 0.15f * std::sin(0.2f * x) * std::sin(0.15f * y);
  const float length = std::sqrt(dx * dx + dy * dy + 1.0f);
  return {-dx / length, -dy / length, 1.0f / length};
}

// A (cells+1)^2 vertex grid over [-size/2, size/2]^2 (m).
inline Mesh test_terrain(int cells, float size) {
  Mesh mesh;
  mesh.name = "terrain";
  const int n = cells + 1;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x = -size / 2 + size * static_cast<float>(i) / static_cast<float>(cells);
      const float y = -size / 2 + size * static_cast<float>(j) / static_cast<float>(cells);
      mesh.positions.push_back({x, y, test_height(x, y)});
      mesh.normals.push_back(test_normal(x, y));
    }
  }
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const auto v = static_cast<std::uint32_t>(j * n + i);
      const auto w = static_cast<std::uint32_t>(n);
      mesh.triangles.push_back({v, v + 1, v + w + 1});
      mesh.triangles.push_back({v, v + w + 1, v + w});
    }
  }
  mesh.triangle_material.assign(mesh.triangles.size(), 0);
  mesh.materials = {Material{"soil", {0.20f, 0.14f, 0.08f}, 0.95f, 0.0f}};
  return mesh;
}

// Axis-aligned box with flat normals (24 vertices), material `slot`.
inline void add_box(Mesh& mesh, std::array<float, 3> low, std::array<float, 3> high, std::uint16_t slot) {
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::array<float, 3> normal{};
      normal[axis] = side ? 1.0f : -1.0f;
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      for (int corner = 0; corner < 4; ++corner) {
        std::array<float, 3> p{};
        p[axis] = side ? high[axis] : low[axis];
        p[u] = (corner == 1 || corner == 2) ? high[u] : low[u];
        p[v] = (corner >= 2) ? high[v] : low[v];
        mesh.positions.push_back(p);
        mesh.normals.push_back(normal);
      }
      // (u, v) corners 0,1,2,3 are counter-clockwise seen from +axis.
      if (side) {
        mesh.triangles.push_back({base, base + 1, base + 2});
        mesh.triangles.push_back({base, base + 2, base + 3});
      } else {
        mesh.triangles.push_back({base, base + 2, base + 1});
        mesh.triangles.push_back({base, base + 3, base + 2});
      }
      mesh.triangle_material.push_back(slot);
      mesh.triangle_material.push_back(slot);
    }
  }
}

// A fan of `count` triangles around (0, 0, height) facing +z, radius `radius` (m).
inline void add_fan(Mesh& mesh, float height, float radius, int count, std::uint16_t slot) {
  const auto center = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back({0, 0, height});
  mesh.normals.push_back({0, 0, 1});
  for (int k = 0; k < count; ++k) {
    const float angle = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) / static_cast<float>(count);
    mesh.positions.push_back({radius * std::cos(angle), radius * std::sin(angle), height});
    mesh.normals.push_back({0, 0, 1});
  }
  for (int k = 0; k < count; ++k) {
    mesh.triangles.push_back(
        {center, center + 1 + static_cast<std::uint32_t>(k), center + 1 + static_cast<std::uint32_t>((k + 1) % count)});
    mesh.triangle_material.push_back(slot);
  }
}

// Variant 0: stem, leaf, petals, disk (4 materials); 1: a taller one without leaf (3);
// 2: a bush-like box pair (2).
inline std::vector<Mesh> test_models() {
  const Material petal{"petal", {0.95f, 0.70f, 0.05f}, 0.5f, 0.3f};
  const Material disk{"disk", {0.25f, 0.12f, 0.03f}, 0.8f, 0.0f};
  const Material stem{"stem", {0.15f, 0.45f, 0.08f}, 0.6f, 0.1f};
  const Material leaf{"leaf", {0.10f, 0.50f, 0.10f}, 0.6f, 0.3f};
  std::vector<Mesh> models(3);
  models[0].name = "sunflower_a";
  models[0].materials = {stem, leaf, petal, disk};
  add_box(models[0], {-0.02f, -0.02f, 0.0f}, {0.02f, 0.02f, 1.5f}, 0);
  add_box(models[0], {0.02f, -0.01f, 0.7f}, {0.30f, 0.01f, 0.72f}, 1);
  add_fan(models[0], 1.50f, 0.25f, 12, 2);
  add_fan(models[0], 1.51f, 0.12f, 8, 3);
  models[1].name = "sunflower_b";
  models[1].materials = {stem, petal, disk};
  add_box(models[1], {-0.025f, -0.025f, 0.0f}, {0.025f, 0.025f, 2.0f}, 0);
  add_fan(models[1], 2.00f, 0.30f, 14, 1);
  add_fan(models[1], 2.01f, 0.15f, 8, 2);
  models[2].name = "bush";
  models[2].materials = {stem, leaf};
  add_box(models[2], {-0.03f, -0.03f, 0.0f}, {0.03f, 0.03f, 0.4f}, 0);
  add_box(models[2], {-0.3f, -0.3f, 0.4f}, {0.3f, 0.3f, 0.8f}, 1);
  return models;
}

// Deterministic pseudo-random value in [0, 1) for instance i and channel c.
inline float test_random(std::uint64_t i, std::uint64_t c) {
  std::uint64_t h = i * 0x9E3779B97F4A7C15ull + c * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return static_cast<float>(h >> 40) / static_cast<float>(1ull << 24);
}

// A scene of `instance_count` instances over a `size` m square terrain of cells^2 cells,
// streamed in batches of `batch_size`.
inline Scene make_test_scene(std::uint64_t instance_count, int cells = 32, float size = 40.0f,
                             std::size_t batch_size = 4096) {
  Scene scene;
  scene.name = "blender_test";
  scene.terrain = test_terrain(cells, size);
  scene.models = test_models();
  const auto variants = static_cast<std::uint64_t>(scene.models.size());
  scene.instances = [=](const std::function<void(const InstanceBatch&)>& sink) {
    InstanceBatch batch;
    batch.reserve(batch_size);
    for (std::uint64_t i = 0; i < instance_count; ++i) {
      const float x = (test_random(i, 0) - 0.5f) * size * 0.95f;
      const float y = (test_random(i, 1) - 0.5f) * size * 0.95f;
      batch.push_back(x, y, test_height(x, y), test_random(i, 2) * 2.0f * std::numbers::pi_v<float>,
                      0.8f + 0.4f * test_random(i, 3), static_cast<std::uint16_t>(i % variants), 0);
      if (batch.size() == batch_size) {
        sink(batch);
        batch.clear();
      }
    }
    if (!batch.empty()) sink(batch);
  };
  scene.camera.position = {-0.5 * size, -0.5 * size, 0.25 * size};
  scene.camera.target = {0, 0, 0};
  scene.camera.fov_degrees = 50;
  scene.sun.azimuth_degrees = 135;
  scene.sun.elevation_degrees = 35;
  scene.render.width = 160;
  scene.render.height = 120;
  scene.georeference = {{"crs_wkt", "PROJCS[\"WGS 84 / UTM zone 32N\"]"},
                        {"srid", "EPSG:32632"},
                        {"origin_easting", "500000.5"},
                        {"origin_northing", "5100000.25"},
                        {"origin_latitude", "46.0436"},
                        {"origin_longitude", "9.0"},
                        {"units", "meters"}};
  return scene;
}

// `whole`, failing with an Error when it would hand over batch number `failing_batch` (1-based):
// placement breaking off midway.
inline InstanceStream failing_at_batch(InstanceStream whole, int failing_batch) {
  return [whole, failing_batch](const InstanceSink& sink) {
    int batches = 0;
    whole([&](const InstanceBatch& batch) {
      if (++batches == failing_batch) throw Error("placement failed on purpose");
      sink(batch);
    });
  };
}

}  // namespace wangscape::testing
