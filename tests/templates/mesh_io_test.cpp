#include "templates/mesh_io.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "templates/sunflower.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("wangscape_mesh_io_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return path;
  }

  // The message of the Error that loading `path` throws ("" if none).
  static std::string load_error(const fs::path& path) {
    try {
      load_mesh(path);
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }

  fs::path dir_;
};

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' should contain '" << part << "'";
}

std::string little_endian_bytes(const void* data, std::size_t size) {
  // The tests run on little-endian hosts only (x86-64, arm64); PLY binary_little_endian matches.
  return std::string(static_cast<const char*>(data), size);
}

TEST_F(MeshIo, ObjRoundTripKeepsEveryTriangle) {
  const Mesh original = make_sunflower(3, 1, 600).mesh;
  fs::path path = dir_ / "flower.obj";
  {
    std::ofstream out(path, std::ios::binary);
    write_obj(out, original);
  }
  const Mesh loaded = load_mesh(path);
  ASSERT_EQ(loaded.triangle_count(), original.triangle_count());
  // OBJ lists materials in order of first use; compare them by name.
  ASSERT_EQ(loaded.materials.size(), original.materials.size());
  for (std::size_t t = 0; t < original.triangles.size(); ++t) {
    const Material& loaded_material = loaded.materials[loaded.triangle_material[t]];
    const Material& original_material = original.materials[original.triangle_material[t]];
    EXPECT_EQ(loaded_material.name, original_material.name);
    EXPECT_EQ(loaded_material.base_color, original_material.base_color);  // sunflower names keep colors
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(loaded.positions[loaded.triangles[t][c]], original.positions[original.triangles[t][c]]);
      const auto& a = loaded.normals[loaded.triangles[t][c]];
      const auto& b = original.normals[original.triangles[t][c]];
      for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(a[axis], b[axis], 1e-6);
    }
  }
}

TEST_F(MeshIo, PlyRoundTripIsExactInBothFormats) {
  const Mesh original = make_sunflower(4, 2, 600).mesh;
  for (PlyFormat format : {PlyFormat::binary_little_endian, PlyFormat::ascii}) {
    const fs::path path = dir_ / (format == PlyFormat::ascii ? "ascii.PLY" : "binary.ply");
    {
      std::ofstream out(path, std::ios::binary);
      write_ply(out, original, format);
    }
    const Mesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.positions, original.positions);
    EXPECT_EQ(loaded.triangles, original.triangles);
    EXPECT_EQ(loaded.triangle_material, original.triangle_material);
    ASSERT_EQ(loaded.normals.size(), original.normals.size());
    for (std::size_t v = 0; v < original.normals.size(); ++v) {
      for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(loaded.normals[v][axis], original.normals[v][axis], 1e-6);
    }
    ASSERT_EQ(loaded.materials.size(), 4u);
    for (std::size_t m = 0; m < 4; ++m) {
      EXPECT_EQ(loaded.materials[m].name, original.materials[m].name);
      EXPECT_EQ(loaded.materials[m].base_color, original.materials[m].base_color);
    }
  }
}

TEST_F(MeshIo, ObjPolygonsNegativeIndicesAndMissingNormals) {
  // A unit square as one quad (negative indices), then a triangle with texture coordinates.
  const fs::path path = write("square.obj",
                              "# comment\r\n"
                              "o square\n"
                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                              "vt 0 0\n"
                              "usemtl petal\n"
                              "f -4 -3 -2 -1\n"
                              "g other\n"
                              "usemtl custom\n"
                              "v 2 0 0\n"
                              "f 2/1 5/1 3/1\n");
  const Mesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.triangle_count(), 3u);
  ASSERT_EQ(mesh.vertex_count(), 5u);
  ASSERT_EQ(mesh.normals.size(), 5u);
  for (const auto& n : mesh.normals) {
    EXPECT_NEAR(n[2], 1.0, 1e-6);  // flat and counter-clockwise seen from +z
  }
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.materials[0].name, "petal");
  EXPECT_EQ(mesh.materials[0].base_color, sunflower_materials()[sunflower_petal].base_color);
  EXPECT_EQ(mesh.materials[1].name, "custom");
  EXPECT_EQ(mesh.triangle_material, (std::vector<std::uint16_t>{0, 0, 1}));
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST_F(MeshIo, ObjFileNormalsSplitVertices) {
  // A position used with two different normals becomes two vertices: 6 distinct pairs here.
  const fs::path path = write("split.obj",
                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                              "vn 0 0 2\nvn 0 -1 0\n"
                              "f 1//1 2//1 3//1\n"
                              "f 1//2 4//2 2//2\n");
  const Mesh mesh = load_mesh(path);
  EXPECT_EQ(mesh.vertex_count(), 6u);
  EXPECT_EQ(mesh.positions[0], mesh.positions[3]);
  EXPECT_EQ(mesh.normals[0], (std::array<float, 3>{0, 0, 1}));  // normalized
  EXPECT_EQ(mesh.normals[3], (std::array<float, 3>{0, -1, 0}));
}

TEST_F(MeshIo, ObjErrorsNameFileAndLine) {
  expect_contains(load_error(write("range.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n")),
                  "range.obj:3: vertex index 3 out of range");
  expect_contains(load_error(write("negative.obj", "v 0 0 0\nf -1 -2 -3\n")), "negative.obj:2:");
  expect_contains(load_error(write("number.obj", "v 0 0 0\nv 1 x 0\n")), "number.obj:2: 'x' is not a finite number");
  expect_contains(load_error(write("short.obj", "v 0 0\n")), "short.obj:1: expected 3 numbers");
  expect_contains(load_error(write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")), "two.obj:3: a face needs at least 3");
  expect_contains(load_error(write("zero.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n")), "zero.obj:4:");
  expect_contains(load_error(write("normal.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1//1 2//1 3//1\n")),
                  "normal.obj:4: normal index 1 out of range");
  expect_contains(load_error(write("empty.obj", "v 0 0 0\n")), "empty.obj: no faces");
}

TEST_F(MeshIo, PlyBinaryWithExtraPropertiesAndElements) {
  // Vertices carry colors, faces a quad and a triangle, plus an unknown element to skip.
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\ncomment made by hand\n"
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& corner : corners) {
    bytes += little_endian_bytes(corner, sizeof corner);
    bytes += std::string("\x10\x20\x30", 3);
  }
  const auto face = [&](std::initializer_list<std::int32_t> indices) {
    bytes += char(indices.size());
    for (std::int32_t i : indices) bytes += little_endian_bytes(&i, 4);
    bytes += char(2);  // two texcoords
    const float uv[2] = {0.5f, 0.5f};
    bytes += little_endian_bytes(uv, sizeof uv);
  };
  face({0, 1, 2, 3});
  face({1, 2, 3});
  const std::int32_t edge[2] = {0, 1};
  bytes += little_endian_bytes(edge, sizeof edge);
  const Mesh mesh = load_mesh(write("hand.ply", bytes));
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.triangle_count(), 3u);
  EXPECT_EQ(mesh.positions[2], (std::array<float, 3>{1, 1, 0}));
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].name, "default");
  for (const auto& n : mesh.normals) EXPECT_NEAR(n[2], 1.0, 1e-6);
}

TEST_F(MeshIo, PlyAsciiWithNormalsAndPolygons) {
  const Mesh mesh = load_mesh(write("ascii.ply",
                                    "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\n"
                                    "property double x\nproperty double y\nproperty double z\n"
                                    "property float nx\nproperty float ny\nproperty float nz\n"
                                    "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
                                    "0 0 0 0 0 3\n1 0 0 0 0 1\n\n1 1 0 0 0 1\n0 1 0 0 0 1\n4 0 1 2 3\n"));
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.normals[0], (std::array<float, 3>{0, 0, 1}));
}

TEST_F(MeshIo, PlyErrorsNameFileAndElement) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_contains(load_error(write("range.ply", header + "0 0 0\n1 0 0\n1 1 0\n3 0 1 7\n")),
                  "range.ply:13: face 0: vertex index 7");
  expect_contains(load_error(write("few.ply", header + "0 0 0\n1 0\n1 1 0\n3 0 1 2\n")),
                  "few.ply:11: vertex 1: too few values");
  expect_contains(load_error(write("cut.ply", header + "0 0 0\n1 0 0\n")),
                  "cut.ply:12: vertex 2: unexpected end of file");
  expect_contains(load_error(write("nan.ply", header + "0 0 0\n1 nan 0\n1 1 0\n3 0 1 2\n")),
                  "nan.ply:11: vertex 1: 'nan' is not a finite number");

  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float one_vertex[3] = {0, 0, 0};
  binary += little_endian_bytes(one_vertex, sizeof one_vertex);
  binary += "\x01\x02";  // the second vertex is cut short
  expect_contains(load_error(write("cut_binary.ply", binary)), "cut_binary.ply: vertex 1: unexpected end of file");

  expect_contains(load_error(write("big.ply", "ply\nformat binary_big_endian 1.0\nend_header\n")),
                  "big.ply:2: unsupported PLY format 'binary_big_endian'");
  expect_contains(load_error(write("nomagic.ply", "solid\n")), "nomagic.ply:1: not a PLY file");
  expect_contains(load_error(write("noxyz.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                   "element face 0\nproperty list uchar int vertex_indices\nend_header\n0\n")),
                  "noxyz.ply: element vertex has no scalar property 'y'");
  expect_contains(
      load_error(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")),
      "type.ply:4: unknown property type 'quad'");
  expect_contains(load_error(write("header.ply", "ply\nformat ascii 1.0\nelement vertex 1\n")),
                  "header.ply:3: unexpected end of file in the PLY header");
}

TEST_F(MeshIo, UserModelsAreScaledTurnedAndGrounded) {
  // A y-up triangle in centimeters, floating above its own origin.
  const fs::path path = write("yup.obj",
                              "v 100 50 0\nv 300 50 0\nv 100 250 0\n"
                              "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
                              "f 1//1 2//2 3//3\n");
  const Mesh mesh = load_user_model(path, {0.01f, true, true});
  const MeshExtent extent = measure_extent(mesh);
  EXPECT_NEAR(extent.min[2], 0.0, 1e-6);
  EXPECT_NEAR(extent.height, 2.0, 1e-5);  // 200 cm of +y became 2 m of +z
  EXPECT_NEAR(extent.min[0], -1.0, 1e-5);
  EXPECT_NEAR(extent.max[0], 1.0, 1e-5);
  EXPECT_NEAR(extent.min[1] + extent.max[1], 0.0, 1e-6);
  EXPECT_EQ(mesh.normals[0], (std::array<float, 3>{0, -1, 0}));  // +z of a y-up file faces -y
  // The winding still agrees with the normals after the turn.
  const auto& p = mesh.positions;
  const auto& t = mesh.triangles[0];
  const float e1[3] = {p[t[1]][0] - p[t[0]][0], p[t[1]][1] - p[t[0]][1], p[t[1]][2] - p[t[0]][2]};
  const float e2[3] = {p[t[2]][0] - p[t[0]][0], p[t[2]][1] - p[t[0]][1], p[t[2]][2] - p[t[0]][2]};
  EXPECT_LT(e1[2] * e2[0] - e1[0] * e2[2], 0.0f);  // y component of the face normal
  expect_contains(
      [&] {
        try {
          load_user_model(path, {0.0f, false, true});
        } catch (const Error& error) {
          return std::string(error.what());
        }
        return std::string();
      }(),
      "yup.obj: model scale 0");
}

TEST_F(MeshIo, LoadRejectsUnknownFormatAndMissingFile) {
  expect_contains(load_error(write("model.stl", "solid x\n")), "model.stl: unknown mesh format '.stl'");
  expect_contains(load_error(dir_ / "missing.obj"), "missing.obj: cannot open");
}

}  // namespace
}  // namespace wangscape
