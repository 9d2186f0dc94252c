#include "templates/sunflower.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace wangscape {
namespace {

using Vec = std::array<float, 3>;

Vec subtract(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) { return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]; }
double length(const Vec& a) { return std::sqrt(dot(a, a)); }

// Checks every structural property a sunflower mesh must have, for any budget and seed.
void expect_well_formed(const SunflowerModel& model) {
  const Mesh& mesh = model.mesh;
  SCOPED_TRACE(mesh.name);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.triangle_material.size(), mesh.triangles.size());
  ASSERT_EQ(mesh.materials.size(), 4u);

  for (const Vec& n : mesh.normals) ASSERT_NEAR(length(n), 1.0, 1e-4);
  std::vector<int> material_use(mesh.materials.size(), 0);
  std::size_t degenerate = 0, facing_away = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::uint32_t v : tri) ASSERT_LT(v, mesh.positions.size());
    ASSERT_LT(mesh.triangle_material[t], mesh.materials.size());
    ++material_use[mesh.triangle_material[t]];
    const Vec face = cross(subtract(mesh.positions[tri[1]], mesh.positions[tri[0]]),
                           subtract(mesh.positions[tri[2]], mesh.positions[tri[0]]));
    const double area = 0.5 * length(face);
    if (area < 1e-10) ++degenerate;  // m^2: a tenth of a square millimeter's thousandth
    // Smooth normals must agree with the winding (counter-clockwise seen from outside).
    const Vec& n0 = mesh.normals[tri[0]];
    const Vec& n1 = mesh.normals[tri[1]];
    const Vec& n2 = mesh.normals[tri[2]];
    const Vec average = {n0[0] + n1[0] + n2[0], n0[1] + n1[1] + n2[1], n0[2] + n1[2] + n2[2]};
    if (dot(face, average) <= 0) ++facing_away;
  }
  EXPECT_LE(degenerate, mesh.triangles.size() / 1000) << "degenerate triangles";
  EXPECT_LE(facing_away, mesh.triangles.size() / 100) << "triangles whose normals disagree with their winding";
  for (std::size_t m = 0; m < material_use.size(); ++m) {
    EXPECT_GT(material_use[m], 0) << "material " << mesh.materials[m].name << " unused";
  }
}

TEST(Sunflower, SameSeedGivesIdenticalMeshes) {
  const SunflowerOptions options{11, 42, 5000};
  const auto first = make_sunflower_variants(options);
  const auto second = make_sunflower_variants(options);
  ASSERT_EQ(first.size(), 11u);
  ASSERT_EQ(second.size(), 11u);
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].mesh.positions, second[i].mesh.positions);
    EXPECT_EQ(first[i].mesh.normals, second[i].mesh.normals);
    EXPECT_EQ(first[i].mesh.triangles, second[i].mesh.triangles);
    EXPECT_EQ(first[i].mesh.triangle_material, second[i].mesh.triangle_material);
    EXPECT_EQ(first[i].extent.radius, second[i].extent.radius);
  }
}

TEST(Sunflower, DifferentSeedsAndVariantsDiffer) {
  const auto a = make_sunflower_variants({11, 1, 2000});
  const auto b = make_sunflower_variants({11, 2, 2000});
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NE(a[i].mesh.positions, b[i].mesh.positions) << "variant " << i << " ignores the seed";
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(a[i].extent.height, a[j].extent.height) << "variants " << i << " and " << j;
      EXPECT_NE(a[i].mesh.positions, a[j].mesh.positions) << "variants " << i << " and " << j;
    }
  }
}

TEST(Sunflower, VariantsAreTheSingleModels) {
  const auto variants = make_sunflower_variants({3, 9, 1000});
  const SunflowerModel single = make_sunflower(9, 2, 1000);
  EXPECT_EQ(variants[2].mesh.positions, single.mesh.positions);
  EXPECT_EQ(variants[2].mesh.triangles, single.mesh.triangles);
}

class SunflowerBudget : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SunflowerBudget, HonouredAndWellFormed) {
  const std::size_t budget = GetParam();
  for (const SunflowerModel& model : make_sunflower_variants({11, 7, budget})) {
    EXPECT_LE(model.mesh.triangle_count(), budget);
    EXPECT_GE(double(model.mesh.triangle_count()), 0.9 * double(budget));
    expect_well_formed(model);
  }
}

INSTANTIATE_TEST_SUITE_P(Budgets, SunflowerBudget, ::testing::Values(500, 5000, 35000));

TEST(Sunflower, SmallBudgetsHonouredOverManySeeds) {
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    for (std::size_t budget : {kSunflowerMinimumTriangleBudget, std::size_t(450), std::size_t(777)}) {
      const SunflowerModel model = make_sunflower(seed, int(seed % 11), budget);
      EXPECT_LE(model.mesh.triangle_count(), budget) << "seed " << seed;
      EXPECT_GE(double(model.mesh.triangle_count()), 0.9 * double(budget)) << "seed " << seed;
      EXPECT_GE(model.floret_count, 8) << "seed " << seed;
    }
  }
}

TEST(Sunflower, CloseUpsSpendTheirTrianglesOnFlorets) {
  const SunflowerModel model = make_sunflower(3, 0, 35000);
  EXPECT_GT(model.floret_count, 2000);
}

// Realistic sizes over many seeds: stems 1.5-3 m, heads 0.1-0.4 m, facing +x and drooping.
TEST(Sunflower, SizesAndPoseInRealisticRanges) {
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    for (const SunflowerModel& model : make_sunflower_variants({11, seed, kSunflowerMinimumTriangleBudget})) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " " + model.mesh.name);
      EXPECT_GE(model.extent.height, 1.5f);
      EXPECT_LE(model.extent.height, 3.0f);
      EXPECT_GE(model.extent.min[2], -0.01f) << "model reaches below the ground";
      EXPECT_GE(model.head_diameter, 0.1f);
      EXPECT_LE(model.head_diameter, 0.4f);
      EXPECT_LT(model.disk_diameter, model.head_diameter);
      EXPECT_GT(model.extent.radius, 0.05f);
      EXPECT_LT(model.extent.radius, 1.0f);
      EXPECT_GT(model.crown_radius, 0.25f * model.head_diameter);
      EXPECT_LE(model.crown_radius, model.extent.radius);
      EXPECT_GT(model.head_facing[0], 0.6f) << "head should face roughly +x";
      EXPECT_LT(model.head_facing[2], 0.2f) << "head should droop or face level";

      // The petal tips span the head diameter as measured on the mesh.
      const Mesh& mesh = model.mesh;
      double petal_reach = 0, disk_reach = 0;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const std::uint16_t m = mesh.triangle_material[t];
        for (std::uint32_t v : mesh.triangles[t]) {
          const double d = length(subtract(mesh.positions[v], model.head_center));
          if (m == sunflower_petal) petal_reach = std::max(petal_reach, d);
          if (m == sunflower_disk) disk_reach = std::max(disk_reach, d);
        }
      }
      EXPECT_GE(2 * petal_reach, 0.1);
      EXPECT_LE(2 * petal_reach, 0.4);
      EXPECT_LT(disk_reach, petal_reach);
    }
  }
}

// Outside is outside: the stem's normals point away from its axis, the disk's toward where the
// head faces, and most petal fronts too.
TEST(Sunflower, NormalsPointOutward) {
  for (const SunflowerModel& model : make_sunflower_variants({11, 12, 5000})) {
    const Mesh& mesh = model.mesh;
    std::size_t stem_checked = 0, stem_outward = 0, disk = 0, disk_front = 0, petal = 0, petal_front = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t v : mesh.triangles[t]) {
        const Vec& p = mesh.positions[v];
        const Vec& n = mesh.normals[v];
        switch (mesh.triangle_material[t]) {
          case sunflower_stem:
            if (p[2] < 0.05f) {  // near the base, where the stem axis is the z axis
              ++stem_checked;
              stem_outward += n[0] * p[0] + n[1] * p[1] > 0;
            }
            break;
          case sunflower_disk:
            ++disk;
            disk_front += dot(n, model.head_facing) > 0;
            break;
          case sunflower_petal:
            ++petal;
            petal_front += dot(n, model.head_facing) > 0;
            break;
          default:
            break;
        }
      }
    }
    SCOPED_TRACE(mesh.name);
    EXPECT_GT(stem_checked, 0u);
    EXPECT_EQ(stem_outward, stem_checked);
    EXPECT_GT(disk_front, 0.99 * double(disk));
    EXPECT_GT(petal_front, 0.7 * double(petal));
  }
}

TEST(Sunflower, ExtentIsTheTightRadiusAndTop) {
  const SunflowerModel model = make_sunflower(5, 4, 2000);
  float top = 0, radius = 0;
  for (const Vec& p : model.mesh.positions) {
    top = std::max(top, p[2]);
    radius = std::max(radius, std::hypot(p[0], p[1]));
  }
  EXPECT_FLOAT_EQ(model.extent.height, top);
  EXPECT_NEAR(model.extent.radius, radius, 1e-6);
}

TEST(Sunflower, MaterialsAreNamedAndColored) {
  const auto materials = sunflower_materials();
  ASSERT_EQ(materials.size(), 4u);
  EXPECT_EQ(materials[sunflower_petal].name, "petal");
  EXPECT_EQ(materials[sunflower_disk].name, "disk");
  EXPECT_EQ(materials[sunflower_stem].name, "stem");
  EXPECT_EQ(materials[sunflower_leaf].name, "leaf");
  const auto& yellow = materials[sunflower_petal].base_color;
  EXPECT_GT(yellow[0], yellow[1]);
  EXPECT_GT(yellow[1], 5 * yellow[2]);
  const auto& brown = materials[sunflower_disk].base_color;
  EXPECT_LT(brown[0] + brown[1] + brown[2], 0.5f);
  for (std::uint16_t green : {sunflower_stem, sunflower_leaf}) {
    const auto& c = materials[green].base_color;
    EXPECT_GT(c[1], c[0]);
    EXPECT_GT(c[1], c[2]);
  }
}

TEST(Sunflower, RejectsBadOptions) {
  try {
    make_sunflower(1, 0, 399);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("399"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("400"), std::string::npos) << error.what();
  }
  EXPECT_THROW(make_sunflower(1, 0, kSunflowerMaximumTriangleBudget + 1), Error);
  EXPECT_THROW(make_sunflower_variants({0, 1, 5000}), Error);
}

}  // namespace
}  // namespace wangscape
