// The procedural plants of a meadow (grass clumps, wildflowers) and the kinds a species names:
// deterministic, within their triangle budgets, well formed, every material used, measured.
#include "templates/plants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/vecmath.h"
#include "templates/grass.h"
#include "templates/sunflower.h"
#include "templates/wildflower.h"

namespace wangscape {
namespace {

constexpr PlantKind kMeadowKinds[] = {PlantKind::grass, PlantKind::wildflower};

// Indices in range, unit normals, few degenerate triangles, extent as measured, on the ground.
void expect_well_formed(const PlantModel& model) {
  const Mesh& mesh = model.mesh;
  SCOPED_TRACE(mesh.name);
  ASSERT_FALSE(mesh.triangles.empty());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.triangle_material.size(), mesh.triangles.size());
  for (const auto& n : mesh.normals) ASSERT_NEAR(length(n), 1.0f, 1e-4f);
  std::size_t degenerate = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::uint32_t v : mesh.triangles[t]) ASSERT_LT(v, mesh.positions.size());
    ASSERT_LT(mesh.triangle_material[t], mesh.materials.size());
    const auto& [a, b, c] = mesh.triangles[t];
    if (length(cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a])) < 2e-10f)
      ++degenerate;
  }
  EXPECT_LE(degenerate, mesh.triangles.size() / 200) << "degenerate triangles";
  const MeshExtent measured = measure_extent(mesh);
  EXPECT_EQ(model.extent.radius, measured.radius);
  EXPECT_EQ(model.extent.height, measured.height);
  EXPECT_GE(measured.min[2], -1e-6f) << "below the ground";
}

TEST(Plants, KindsByName) {
  for (const auto kind : {PlantKind::sunflower, PlantKind::grass, PlantKind::wildflower})
    EXPECT_EQ(find_plant_kind(plant_kind_name(kind)), kind);
  EXPECT_FALSE(find_plant_kind("dandelion"));
  EXPECT_FALSE(find_plant_kind(""));
}

TEST(Plants, SameSeedGivesIdenticalMeshes) {
  for (const auto kind : kMeadowKinds) {
    const auto a = make_plant_variants(kind, 42, 5, 900);
    const auto b = make_plant_variants(kind, 42, 5, 900);
    ASSERT_EQ(a.size(), 5u);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].mesh.positions, b[i].mesh.positions);
      EXPECT_EQ(a[i].mesh.normals, b[i].mesh.normals);
      EXPECT_EQ(a[i].mesh.triangles, b[i].mesh.triangles);
      EXPECT_EQ(a[i].mesh.triangle_material, b[i].mesh.triangle_material);
    }
  }
}

TEST(Plants, VariantsAndSeedsDiffer) {
  for (const auto kind : kMeadowKinds) {
    const auto a = make_plant_variants(kind, 1, 6, 900);
    const auto b = make_plant_variants(kind, 2, 6, 900);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_NE(a[i].mesh.positions, b[i].mesh.positions) << a[i].mesh.name << " ignores the seed";
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(a[i].extent.height, a[j].extent.height) << i << " vs " << j;
    }
  }
}

// At most the budget, and close to it: grass within one blade (at most 20 triangles), a
// wildflower within a quarter (its tessellation steps; the sunflower fills with florets).
TEST(Plants, TriangleBudgetsAreMetOverSeedsAndBudgets) {
  for (const auto kind : kMeadowKinds) {
    const auto range = triangle_budget_range(kind);
    for (const std::size_t budget : {range.minimum, std::size_t(400), std::size_t(1000), range.default_budget,
                                     std::size_t(4321), std::size_t(9600)}) {
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        for (const auto& model : make_plant_variants(kind, seed, 3, budget)) {
          SCOPED_TRACE(model.mesh.name + " budget " + std::to_string(budget));
          EXPECT_LE(model.mesh.triangle_count(), budget);
          if (kind == PlantKind::grass)
            EXPECT_GE(model.mesh.triangle_count() + 20, budget);
          else
            EXPECT_GE(model.mesh.triangle_count(), budget * 3 / 4);
          expect_well_formed(model);
        }
      }
    }
  }
}

TEST(Plants, BudgetsOutOfRangeAreRefused) {
  for (const auto kind : kMeadowKinds) {
    const auto range = triangle_budget_range(kind);
    EXPECT_THROW(make_plant_variants(kind, 1, 1, range.minimum - 1), Error);
    EXPECT_THROW(make_plant_variants(kind, 1, 1, range.maximum + 1), Error);
    EXPECT_THROW(make_plant_variants(kind, 1, 0, range.default_budget), Error);
    EXPECT_LE(range.minimum, range.default_budget);
    EXPECT_LE(range.default_budget, range.maximum);
  }
}

// Sizes of the real plants: a grass clump 0.25-0.7 m tall reaching out under 0.6 m, a
// dandelion 0.1-0.4 m tall with a rosette under 0.25 m; every material in use.
TEST(Plants, ExtentsAndMaterialsAreThoseOfMeadowPlants) {
  const struct {
    PlantKind kind;
    float min_height, max_height, max_radius;
    std::size_t materials;
  } expected[] = {{PlantKind::grass, 0.25f, 0.7f, 0.6f, grass_materials().size()},
                  {PlantKind::wildflower, 0.1f, 0.4f, 0.25f, wildflower_materials().size()}};
  for (const auto& e : expected) {
    std::set<std::uint16_t> used;
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
      for (const auto& model : make_plant_variants(e.kind, seed, 8, triangle_budget_range(e.kind).default_budget)) {
        SCOPED_TRACE(model.mesh.name);
        EXPECT_GE(model.extent.height, e.min_height);
        EXPECT_LE(model.extent.height, e.max_height);
        EXPECT_GT(model.extent.radius, 0.02f);
        EXPECT_LE(model.extent.radius, e.max_radius);
        EXPECT_EQ(model.mesh.materials.size(), e.materials);
        used.insert(model.mesh.triangle_material.begin(), model.mesh.triangle_material.end());
      }
    EXPECT_EQ(used.size(), e.materials) << plant_kind_name(e.kind) << ": a material is never used";
  }
}

// The wildflower's head is yellow and sits on top: the highest vertices are petals.
TEST(Plants, WildflowerHeadIsYellowAndOnTop) {
  for (const auto& model : make_plant_variants(PlantKind::wildflower, 5, 6, 1500)) {
    const Mesh& mesh = model.mesh;
    float top_petal = 0, top_leaf = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::uint32_t v : mesh.triangles[t]) {
        float& top = mesh.triangle_material[t] == wildflower_petal ? top_petal : top_leaf;
        top = std::max(top, mesh.positions[v][2]);
      }
    EXPECT_GT(top_petal, top_leaf - 0.02f) << mesh.name;
    const auto& yellow = mesh.materials[wildflower_petal].base_color;
    EXPECT_GT(yellow[0], 4 * yellow[2]);
    EXPECT_GT(yellow[1], 4 * yellow[2]);
  }
}

// The sunflower through the kinds is make_sunflower's mesh.
TEST(Plants, SunflowerKindIsTheSunflower) {
  const auto models = make_plant_variants(PlantKind::sunflower, 3, 2, 800);
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[1].mesh.positions, make_sunflower(3, 1, 800).mesh.positions);
  EXPECT_EQ(models[1].extent.radius, make_sunflower(3, 1, 800).extent.radius);
}

}  // namespace
}  // namespace wangscape
