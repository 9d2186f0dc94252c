#include "templates/mesh_io.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <sstream>
#include <string>

#include "core/color.h"
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

// A seed of the model reader's fuzzer (fuzz/corpus/model_file/NAME): its first byte picks the format.
std::string fuzz_seed(const std::string& name) {
  std::ifstream in(fs::path(WANGSCAPE_SOURCE_DIR) / "fuzz/corpus/model_file" / name, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' should contain '" << part << "'";
}

// How many triangles use the material named `name`.
std::size_t triangles_of(const Mesh& mesh, const std::string& name) {
  std::size_t count = 0;
  for (const std::uint16_t slot : mesh.triangle_material) count += mesh.materials[slot].name == name;
  return count;
}

// The triangles of a mesh as their corners' positions in tenths of a millimetre, sorted: Assimp
// numbers vertices its own way, and its OBJ number parser is not correctly rounded.
std::vector<std::array<long, 9>> corner_positions(const Mesh& mesh) {
  std::vector<std::array<long, 9>> corners;
  for (const auto& t : mesh.triangles) {
    std::array<long, 9> corner{};
    for (int c = 0; c < 9; ++c) corner[c] = std::lround(mesh.positions[t[c / 3]][c % 3] * 1e4);
    corners.push_back(corner);
  }
  std::sort(corners.begin(), corners.end());
  return corners;
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
  // Assimp keeps a file's triangles, grouped by material; compare them as sets of corners.
  EXPECT_EQ(corner_positions(loaded), corner_positions(original));
  // OBJ names the materials (their colours need an MTL, which write_obj does not write).
  ASSERT_EQ(loaded.materials.size(), original.materials.size());
  for (const Material& material : original.materials) EXPECT_EQ(triangles_of(loaded, material.name) > 0, true);
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
    EXPECT_EQ(loaded.positions, original.positions);  // floats written and read bit for bit
    EXPECT_EQ(loaded.triangles, original.triangles);
    EXPECT_EQ(loaded.triangle_material, original.triangle_material);
    ASSERT_EQ(loaded.materials.size(), original.materials.size());
    for (std::size_t m = 0; m < original.materials.size(); ++m) {
      EXPECT_EQ(loaded.materials[m].name, original.materials[m].name);
      EXPECT_EQ(loaded.materials[m].base_color, original.materials[m].base_color);  // comment material lines
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
  ASSERT_EQ(mesh.normals.size(), mesh.vertex_count());
  for (const auto& n : mesh.normals) EXPECT_NEAR(n[2], 1.0, 1e-6);  // flat and counter-clockwise seen from +z
  ASSERT_EQ(mesh.materials.size(), 2u);
  std::vector<std::string> names{mesh.materials[0].name, mesh.materials[1].name};
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"custom", "petal"}));
  // Without an MTL the file gives no colour: Assimp's grey, never the sunflower's by name.
  EXPECT_EQ(mesh.materials[0].base_color, (std::array<float, 3>{0.6f, 0.6f, 0.6f}));
}

TEST_F(MeshIo, ErrorsNameTheFile) {
  expect_contains(load_error(write("range.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n")), "range.obj");
  expect_contains(load_error(write("empty.obj", "v 0 0 0\n")), "empty.obj: ");
  expect_contains(load_error(write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n")), "lines.obj: ");
  // PLY is read by hand (Assimp's PLY reader hangs on a header without end_header, like cut.ply).
  expect_contains(load_error(write("nomagic.ply", "solid\n")), "nomagic.ply:1: not a PLY file");
  expect_contains(load_error(write("cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n")),
                  "cut.ply:4: unexpected end of file in the PLY header");
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
  expect_contains(load_error(write("model.qqq", "nothing a reader knows\n")), "model.qqq: not a model Assimp reads");
  expect_contains(load_error(dir_ / "missing.obj"), "missing.obj: no such model file");
}

// ---- Real models: a subset of Debian's assimp-testmodels and Wangscape's own (tests/data/models) ----

const fs::path kModels = fs::path(WANGSCAPE_SOURCE_DIR) / "tests" / "data" / "models";

void expect_color(const std::array<float, 3>& color, float r, float g, float b) {
  EXPECT_NEAR(color[0], r, 1e-3);
  EXPECT_NEAR(color[1], g, 1e-3);
  EXPECT_NEAR(color[2], b, 1e-3);
}

TEST(ModelImport, EachFormatOfTheSubsetImportsWithItsColours) {
  struct Case {
    const char* file;
    std::size_t triangles;
    const char* material;
    std::array<float, 3> color;
  };
  const Case cases[] = {
      {"cube_usemtl.obj", 12, "mtl2", {1, 1, 1}},  // OBJ with its MTL's Kd
      {"tulip.obj", 10, "head", {0.8f, 0.05f, 0.05f}},
      {"BoxTextured.gltf", 12, "Texture", {1, 1, 1}},  // glTF 2.0, its image beside it
      {"BoxTexturedBinary.glb", 12, "Texture", {1, 1, 1}},
      {"leaf_card.gltf", 2, "leaf", {1, 1, 1}},
      {"tulip_textured.obj", 576, "head", {1, 1, 1}},   // OBJ whose MTL maps an image (map_Kd)
      {"leaf_cross.glb", 6, "leaf", {1, 1, 1}},         // GLB, its image held inside, alpha MASK
      {"cube.ply", 12, "default", {0.5f, 0.5f, 0.5f}},  // PLY ascii: no materials in the file
      {"cube_binary.ply", 12, "default", {0.5f, 0.5f, 0.5f}},
      {"cube_triangulate.dae", 12, "Blue", {0.137255f, 0.403922f, 0.870588f}},  // Collada
      {"box.fbx", 12, "Material_50", {0.992157f, 0.92549f, 0.65098f}},          // FBX binary
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Mesh mesh = load_mesh(kModels / c.file);
    EXPECT_EQ(mesh.triangle_count(), c.triangles);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    const auto found = std::find_if(mesh.materials.begin(), mesh.materials.end(),
                                    [&](const Material& m) { return m.name == c.material; });
    ASSERT_NE(found, mesh.materials.end());
    expect_color(found->base_color, c.color[0], c.color[1], c.color[2]);
    EXPECT_EQ(mesh.name, fs::path(c.file).stem().string());
  }
}

// Issue 38's tulip: the MTL's green stem and red head arrive, on the right triangles.
TEST(ModelImport, TulipTakesItsColoursFromTheMtl) {
  const Mesh mesh = load_mesh(kModels / "tulip.obj");
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(triangles_of(mesh, "stem"), 2u);
  EXPECT_EQ(triangles_of(mesh, "head"), 8u);
  for (const Material& m : mesh.materials) {
    if (m.name == "stem") expect_color(m.base_color, 0.1f, 0.6f, 0.1f);
    if (m.name == "head") expect_color(m.base_color, 0.8f, 0.05f, 0.05f);
    EXPECT_EQ(m.base_color_map, nullptr);
    EXPECT_EQ(m.alpha_cutoff, 0.0f);
  }
  // Used materials only: cube_usemtl.obj's MTL defines two and the file uses a third it lacks.
  EXPECT_EQ(load_mesh(kModels / "cube_usemtl.obj").materials.size(), 3u);
}

// A texel's colour arrives: the leaf card's image, decoded once, with v = 0 at the image's bottom.
TEST(ModelImport, LeafCardTexelsAlphaAndUvsArrive) {
  const Mesh mesh = load_mesh(kModels / "leaf_card.gltf");
  ASSERT_EQ(mesh.materials.size(), 1u);
  const Material& leaf = mesh.materials[0];
  EXPECT_EQ(leaf.alpha_cutoff, 0.5f);  // alphaMode MASK at 0.5
  EXPECT_NEAR(leaf.roughness, 0.8f, 1e-6);
  ASSERT_NE(leaf.base_color_map, nullptr);
  const TextureImage& image = *leaf.base_color_map;
  EXPECT_EQ(image.width, 16);
  EXPECT_EQ(image.height, 16);
  EXPECT_EQ(image.name, "leaf_card");
  // The top quarter of the left half red (200, 30, 30), below it orange (230, 120, 20), the right
  // half transparent.
  const auto top = image.at(0.25f, 0.95f), low = image.at(0.25f, 0.2f), right = image.at(0.75f, 0.5f);
  EXPECT_NEAR(top[0], srgb8_to_linear(200), 1e-6);
  EXPECT_NEAR(top[1], srgb8_to_linear(30), 1e-6);
  EXPECT_NEAR(low[1], srgb8_to_linear(120), 1e-6);
  EXPECT_EQ(top[3], 1.0f);
  EXPECT_EQ(right[3], 0.0f);
  // The card's top-left corner (x -0.5, y 1 in the y-up file) is uv (0, 1).
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  bool found = false;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (mesh.positions[v][0] == -0.5f && mesh.positions[v][1] == 1.0f) {
      found = true;
      EXPECT_EQ(mesh.uvs[v], (std::array<float, 2>{0.0f, 1.0f}));
    }
  EXPECT_TRUE(found);
}

// The textured OBJ's image (map_Kd beside its MTL) and the alpha GLB's (held inside) arrive with
// their texels, v = 0 at the image's bottom: the tulip's head red above and orange below, the
// crossed cards' columns alternately opaque and cut out.
TEST(ModelImport, TexturedObjAndAlphaGlbTexelsArrive) {
  const Mesh tulip = load_mesh(kModels / "tulip_textured.obj");
  ASSERT_EQ(tulip.materials.size(), 2u);
  ASSERT_EQ(tulip.uvs.size(), tulip.positions.size());
  for (const Material& m : tulip.materials) {
    SCOPED_TRACE(m.name);
    if (m.name == "stem") {
      expect_color(m.base_color, 0.1f, 0.6f, 0.1f);
      EXPECT_EQ(m.base_color_map, nullptr);
      continue;
    }
    ASSERT_EQ(m.name, "head");
    ASSERT_NE(m.base_color_map, nullptr);
    EXPECT_EQ(m.alpha_cutoff, 0.0f);  // an OBJ's image is opaque: no cutout
    const TextureImage& image = *m.base_color_map;
    EXPECT_EQ(image.width, 8);
    EXPECT_EQ(image.height, 16);
    const auto top = image.at(0.5f, 0.9f), low = image.at(0.5f, 0.1f);
    EXPECT_NEAR(top[0], srgb8_to_linear(200), 1e-6);
    EXPECT_NEAR(top[1], srgb8_to_linear(30), 1e-6);
    EXPECT_NEAR(low[0], srgb8_to_linear(230), 1e-6);
    EXPECT_NEAR(low[1], srgb8_to_linear(120), 1e-6);
  }
  const Mesh cross = load_mesh(kModels / "leaf_cross.glb");
  ASSERT_EQ(cross.materials.size(), 1u);
  const Material& leaf = cross.materials[0];
  EXPECT_EQ(leaf.alpha_cutoff, 0.5f);
  ASSERT_NE(leaf.base_color_map, nullptr);
  const TextureImage& image = *leaf.base_color_map;
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 32);
  const auto top = image.at(0.05f, 0.95f), low = image.at(0.05f, 0.3f), hole = image.at(0.19f, 0.3f);
  EXPECT_NEAR(top[1], srgb8_to_linear(30), 1e-6);
  EXPECT_NEAR(low[1], srgb8_to_linear(120), 1e-6);
  EXPECT_EQ(top[3], 1.0f);
  EXPECT_EQ(hole[3], 0.0f);
}

// The same image beside a glTF and held inside a GLB: the same texels; the GLB read from memory too.
TEST(ModelImport, HeldAndBesideImagesAreTheSame) {
  const Mesh beside = load_mesh(kModels / "BoxTextured.gltf");
  const Mesh held = load_mesh(kModels / "BoxTexturedBinary.glb");
  ASSERT_NE(beside.materials[0].base_color_map, nullptr);
  ASSERT_NE(held.materials[0].base_color_map, nullptr);
  EXPECT_EQ(beside.materials[0].base_color_map->rgba, held.materials[0].base_color_map->rgba);
  EXPECT_EQ(beside.materials[0].base_color_map->name, "CesiumLogoFlat");
  EXPECT_EQ(held.materials[0].base_color_map->name, "BoxTexturedBinary_0");
  std::ifstream in(kModels / "BoxTexturedBinary.glb", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Mesh from_memory =
      read_model(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), ".glb", "box.glb");
  EXPECT_EQ(from_memory.positions, held.positions);
  EXPECT_EQ(from_memory.materials[0].base_color_map->rgba, held.materials[0].base_color_map->rgba);
}

// A PLY by its first line goes to read_ply whatever its name, and never to Assimp's PLY reader
// (taken out of every importer): the fuzzer's binary PLY told to be glTF crashed in it.
TEST_F(MeshIo, PlyContentIsReadByHandWhateverItsName) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(load_mesh(write("triangle.model", ply)).triangle_count(), 1u);
  EXPECT_EQ(read_model(std::span(reinterpret_cast<const std::uint8_t*>(ply.data()), ply.size()), ".gltf", "t.gltf")
                .triangle_count(),
            1u);
  const std::string seed = fuzz_seed("regress-ply-sniffed-segv.seed");
  ASSERT_GT(seed.size(), 1u);
  try {
    read_model(std::span(reinterpret_cast<const std::uint8_t*>(seed.data()) + 1, seed.size() - 1), ".gltf", "seed");
  } catch (const Error&) {  // a refusal is fine; a crash is not
  }
}

// Assimp 5.2's OBJ reader crashed on a `usemtl` line holding NULs (the fuzzer's seed below): text
// formats with a NUL byte are refused before Assimp sees them, from a file and from memory.
TEST_F(MeshIo, TextModelsWithNulBytesAreRefusedNamingTheLine) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusem" + std::string(2, '\0') + "tl x\nf 1 2 3\n";
  expect_contains(load_error(write("nul.obj", obj)), "nul.obj:4: holds a NUL byte; a .obj file is text");
  expect_contains(load_error(write("nul.dae", "<?xml version=\"1.0\"?>\n<COLLADA>" + std::string(1, '\0'))),
                  "nul.dae:2: holds a NUL byte");
  const std::string seed = fuzz_seed("regress-obj-nul-usemtl-segv.seed");
  ASSERT_GT(seed.size(), 1u);
  try {
    read_model(std::span(reinterpret_cast<const std::uint8_t*>(seed.data()) + 1, seed.size() - 1), ".obj", "seed.obj");
    ADD_FAILURE() << "the seed's NUL bytes should be refused";
  } catch (const Error& error) {
    expect_contains(error.what(), "seed.obj:1: holds a NUL byte");
  }
}

TEST_F(MeshIo, AMissingImageIsAnErrorNamingMaterialAndPath) {
  write("card.mtl", "newmtl leaf\nKd 1 1 1\nmap_Kd no_such_leaf.png\n");
  const fs::path path = write("card.obj",
                              "mtllib card.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                              "usemtl leaf\nf 1/1 2/2 3/3\n");
  const std::string error = load_error(path);
  expect_contains(error, "card.obj:material 'leaf': its image 'no_such_leaf.png' is not at");
  expect_contains(load_error(write("held.obj", "v 0 0 0\n")), "held.obj");
}

}  // namespace
}  // namespace wangscape
