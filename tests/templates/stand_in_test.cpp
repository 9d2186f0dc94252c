#include "templates/stand_in.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "templates/mesh_io.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(WANGSCAPE_SOURCE_DIR) / "tests" / "data" / "models";

std::size_t triangles_of_material(const Mesh& mesh, std::uint16_t material) {
  return std::size_t(std::count(mesh.triangle_material.begin(), mesh.triangle_material.end(), material));
}

// The checks every stand-in passes: at most `max_triangles`, the model's materials and uvs (each
// one a vertex of the model had), a bounding box within the reported error of the model's.
void expect_a_faithful_stand_in(const Mesh& model, const StandIn& stand_in, std::size_t max_triangles) {
  const Mesh& mesh = stand_in.mesh;
  EXPECT_GT(mesh.triangle_count(), 0u);
  EXPECT_LE(mesh.triangle_count(), max_triangles);
  EXPECT_TRUE(std::isfinite(stand_in.error));
  EXPECT_GE(stand_in.error, 0.0);
  ASSERT_EQ(mesh.triangle_material.size(), mesh.triangle_count());
  EXPECT_EQ(mesh.materials.size(), model.materials.size());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.uvs.size(), model.uvs.empty() ? 0u : mesh.positions.size());
  std::set<std::array<float, 5>> model_vertices;
  for (std::size_t v = 0; v < model.positions.size(); ++v)
    model_vertices.insert({model.positions[v][0], model.positions[v][1], model.positions[v][2],
                           model.uvs.empty() ? 0 : model.uvs[v][0], model.uvs.empty() ? 0 : model.uvs[v][1]});
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const std::array<float, 5> vertex{mesh.positions[v][0], mesh.positions[v][1], mesh.positions[v][2],
                                      mesh.uvs.empty() ? 0 : mesh.uvs[v][0], mesh.uvs.empty() ? 0 : mesh.uvs[v][1]};
    EXPECT_TRUE(model_vertices.contains(vertex)) << "vertex " << v << " with its uv is not the model's";
    if (!mesh.uvs.empty()) {
      EXPECT_GE(mesh.uvs[v][0], 0.0f);
      EXPECT_LE(mesh.uvs[v][0], 1.0f);
      EXPECT_GE(mesh.uvs[v][1], 0.0f);
      EXPECT_LE(mesh.uvs[v][1], 1.0f);
    }
  }
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t v : t) ASSERT_LT(v, mesh.positions.size());
  const MeshExtent before = measure_extent(model), after = measure_extent(mesh);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(after.min[axis], before.min[axis], stand_in.error + 1e-6) << "axis " << axis;
    EXPECT_NEAR(after.max[axis], before.max[axis], stand_in.error + 1e-6) << "axis " << axis;
  }
}

// The round tulip (576 triangles: stem and UV-sphere head with uvs) at the proxies' 400 and at 100.
TEST(StandIn, ARoundTulipKeepsItsUvsMaterialsAndBoxWithinItsError) {
  const Mesh tulip = load_mesh(kModels / "tulips" / "tulip_4.obj");
  ASSERT_EQ(tulip.triangle_count(), 576u);
  ASSERT_EQ(tulip.uvs.size(), tulip.positions.size());
  for (const std::size_t budget : {400u, 100u}) {
    SCOPED_TRACE(budget);
    const StandIn stand_in = make_stand_in(tulip, {budget, 1.0 / 16});
    expect_a_faithful_stand_in(tulip, stand_in, budget);
    EXPECT_LT(stand_in.mesh.triangle_count(), tulip.triangle_count());
    EXPECT_GT(triangles_of_material(stand_in.mesh, 0), 0u);  // the stem
    EXPECT_GT(triangles_of_material(stand_in.mesh, 1), 0u);  // the head
    EXPECT_EQ(stand_in.mesh.name, "tulip_4");
    // Within 1/16 of the tulip's 0.78 m height (meshopt's error, scaled to meters).
    EXPECT_LT(stand_in.error, 0.78 / 16);
  }
  // A tight budget beats the target error and the held borders: at most 30 triangles whatever
  // the error (the open stem tube may go: no box check).
  const StandIn tight = make_stand_in(tulip, {30, 1e-6});
  EXPECT_GT(tight.mesh.triangle_count(), 0u);
  EXPECT_LE(tight.mesh.triangle_count(), 30u);
  EXPECT_GT(tight.error, 0.0);
  EXPECT_TRUE(std::isfinite(tight.error));
  // The fewest within a looser error are fewer than within a tighter one.
  EXPECT_LT(make_stand_in(tulip, {400, 0.1}).mesh.triangle_count(),
            make_stand_in(tulip, {400, 0.001}).mesh.triangle_count());
}

// A flat 16 x 16 grid whose triangles hold their own copies of every corner (as some exporters
// write them): welded by position and uv, its inside simplifies away at no error (unwelded, no
// triangle could go); its outline of 64 vertices is held (62 triangles at most).
TEST(StandIn, SeparateCornersAreWeldedFirst) {
  Mesh grid;
  grid.materials.push_back({"leaf", {0.2f, 0.6f, 0.2f}});
  const auto corner = [&](int i, int j) {
    grid.positions.push_back({float(i) / 16, float(j) / 16, 0});
    grid.normals.push_back({0, 0, 1});
    grid.uvs.push_back({float(i) / 16, float(j) / 16});
    return std::uint32_t(grid.positions.size() - 1);
  };
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      grid.triangles.push_back({corner(i, j), corner(i + 1, j), corner(i + 1, j + 1)});
      grid.triangles.push_back({corner(i, j), corner(i + 1, j + 1), corner(i, j + 1)});
      grid.triangle_material.insert(grid.triangle_material.end(), 2, 0);
    }
  const StandIn stand_in = make_stand_in(grid, {400, 1.0 / 16});
  expect_a_faithful_stand_in(grid, stand_in, 400);
  EXPECT_LE(stand_in.mesh.triangle_count(), 62u);
  EXPECT_LT(stand_in.error, 1e-4);
}

TEST(StandIn, FiguresNameEachStandInAsAProxy) {
  const Mesh tulip = load_mesh(kModels / "tulips" / "tulip_1.obj");
  std::vector<StandInFigures> figures;
  const std::vector<Mesh> models{tulip, load_mesh(kModels / "tulip.obj")};
  const auto stand_ins = make_stand_ins(models, {200, 1.0 / 16}, figures);
  ASSERT_EQ(stand_ins.size(), 2u);
  ASSERT_EQ(figures.size(), 2u);
  EXPECT_EQ(stand_ins[0].name, "tulip_1 proxy");
  EXPECT_EQ(figures[1].name, "tulip proxy");
  EXPECT_EQ(figures[0].model_triangles, 576u);
  EXPECT_EQ(figures[0].triangles, stand_ins[0].triangle_count());
  EXPECT_LE(figures[0].triangles, 200u);
  EXPECT_GE(figures[1].error, 0.0);
  // An empty model gives an empty stand-in, not a crash.
  EXPECT_EQ(make_stand_in(Mesh{}).mesh.triangle_count(), 0u);
}

}  // namespace
}  // namespace wangscape
