// The LDI build against the real Embree: simple test meshes (quads, boxes) whose samples are known,
// the 3 x 3 context, shadows, the pack's round trip and its refusal of damaged files, and the same
// bytes on 1 and 2 threads. Suites are named ldi_* so `ctest -R ldi` runs them.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "folder/ldi_info.h"
#include "folder/ldi_pack.h"
#include "folder/pack_light.h"
#include "generator/poisson_tiles.h"
#include "generator/tileset.h"
#include "renders/ldi/ldi_build.h"
#include "renders/ldi/ldi_sheet.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

constexpr double kTile = 4.0;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("wangscape_ldi_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

Material gray(const char* name = "gray") { return {name, {0.5f, 0.5f, 0.5f}, 0.8f, 0.0f}; }

// A horizontal quad [x0, x1] x [y0, y1] at height z (model space = tile-local space for a point at
// the tile's origin with yaw 0 and scale 1).
void add_quad(Mesh& mesh, float x0, float y0, float x1, float y1, float z) {
  const auto base = std::uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  mesh.triangle_material.insert(mesh.triangle_material.end(), {0, 0});
  if (mesh.materials.empty()) mesh.materials.push_back(gray());
}

// An axis-aligned box centred on the model's origin: half-size r, height h.
Mesh box(float r, float h) {
  Mesh mesh;
  mesh.name = "box";
  mesh.materials = {{"yellow", {0.9f, 0.6f, 0.05f}, 0.6f, 0.2f}};
  for (int i = 0; i < 8; ++i) mesh.positions.push_back({(i & 1) ? r : -r, (i & 2) ? r : -r, (i & 4) ? h : 0.0f});
  const std::uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangle_material.push_back(0);
  }
  return mesh;
}

// A set of one tile whose edges all match themselves: its 3 x 3 context is itself nine times.
FilledTileSet one_tile(std::vector<TilePoint> points) {
  FilledTileSet filled;
  filled.set = make_tileset("one", {Tile::edges(0, 0, 0, 0)}, "test");
  filled.tiles = {std::move(points)};
  return filled;
}

// Options for small, fast test builds: 2 levels, 8 directions, a 96-pixel view, no sky rays.
LdiBuildOptions small_options() {
  LdiBuildOptions o;
  o.tile_size = kTile;
  o.view.levels = 2;
  o.view.image_width = 96;
  o.ground = LdiGround::none;
  o.shading.ao_rays = 0;
  o.shading.shadows = false;
  return o;
}

// Where the ray through the centre of pixel (x, y) crosses the plane z = h.
std::array<double, 3> crossing(const LdiFrame& f, int x, int y, double h) {
  std::array<double, 3> o{};
  for (int c = 0; c < 3; ++c)
    o[std::size_t(c)] = f.origin[std::size_t(c)] + (x + 0.5) * f.pixel_size * f.right[std::size_t(c)] -
                        (y + 0.5) * f.pixel_size * f.up[std::size_t(c)];
  const double t = (h - o[2]) / f.forward[2];
  return {o[0] + t * f.forward[0], o[1] + t * f.forward[1], h};
}
bool well_inside(const std::array<double, 3>& p, double margin) {
  return p[0] > margin && p[0] < kTile - margin && p[1] > margin && p[1] < kTile - margin;
}
bool well_outside(const std::array<double, 3>& p, double margin) {
  return p[0] < -margin || p[0] > kTile + margin || p[1] < -margin || p[1] > kTile + margin;
}

TEST(ldi_build, OneHorizontalQuadGivesOneLayerAtItsDepth) {
  Mesh quad;
  add_quad(quad, 0, 0, float(kTile), float(kTile), 1.0f);
  const FilledTileSet filled = one_tile({TilePoint{0, 0, 0, 1, 0, 1}});
  const std::vector<Mesh> models{quad};
  const auto ldis = build_tile_ldis(filled, models, small_options(), 0);
  ASSERT_EQ(ldis.size(), 16u);
  for (const LdiImage& ldi : ldis) {
    const LdiView v = ldi.view();
    const double p = v.frame->pixel_size, margin = 1.5 * p / std::abs(v.frame->forward[2]);
    int checked = 0;
    for (int y = 0; y < int(v.frame->height); ++y)
      for (int x = 0; x < int(v.frame->width); ++x) {
        const auto samples = v.pixel(x, y);
        const auto at = crossing(*v.frame, x, y, 1.0);
        if (well_inside(at, margin)) {
          ASSERT_EQ(samples.size(), 1u) << "pixel " << x << "," << y << " level " << v.frame->level << " dir "
                                        << v.frame->direction << " at " << at[0] << "," << at[1] << " size "
                                        << v.frame->width << "x" << v.frame->height;
          ++checked;
        } else if (well_outside(at, margin)) {
          ASSERT_TRUE(samples.empty()) << "pixel " << x << "," << y;
        }
        for (const DepthPixel& s : samples) {
          // The jitter moves the ray by less than a pixel; depth is exact to 1/65535 of the range.
          EXPECT_NEAR(v.position(x, y, s)[2], 1.0, p + 1e-3);
        }
      }
    EXPECT_GT(checked, 20) << "level " << v.frame->level << " direction " << v.frame->direction;
  }
}

TEST(ldi_build, TwoStackedQuadsGiveTwoSamplesFrontToBack) {
  Mesh quads;
  add_quad(quads, 0, 0, float(kTile), float(kTile), 0.5f);
  add_quad(quads, 0, 0, float(kTile), float(kTile), 1.0f);
  const FilledTileSet filled = one_tile({TilePoint{0, 0, 0, 1, 0, 1}});
  const std::vector<Mesh> models{quads};
  LdiBuildOptions o = small_options();
  o.view.image_width = 192;
  const auto ldis = build_tile_ldis(filled, models, o, 0);
  int both = 0;
  for (const LdiImage& ldi : ldis) {
    const LdiView v = ldi.view();
    const double p = v.frame->pixel_size, margin = 1.5 * p / std::abs(v.frame->forward[2]);
    for (int y = 0; y < int(v.frame->height); ++y)
      for (int x = 0; x < int(v.frame->width); ++x) {
        if (!well_inside(crossing(*v.frame, x, y, 1.0), margin) || !well_inside(crossing(*v.frame, x, y, 0.5), margin))
          continue;
        const auto samples = v.pixel(x, y);
        ASSERT_EQ(samples.size(), 2u);
        EXPECT_LT(samples[0].depth(), samples[1].depth());
        EXPECT_NEAR(v.position(x, y, samples[0])[2], 1.0, p + 1e-3);
        EXPECT_NEAR(v.position(x, y, samples[1])[2], 0.5, p + 1e-3);
        ++both;
      }
  }
  EXPECT_GT(both, 1000);
}

// cohen8 with one tile filled, sampled in a context that does not hold that tile again: what lies
// outside its prism must not be recorded, what lies inside must.
TEST(ldi_build, GeometryOutsideTheCentrePrismIsNotRecorded) {
  FilledTileSet filled;
  filled.set = builtin_tileset("cohen8");
  std::size_t tile = 0;
  int choice = -1;
  for (; tile < filled.set.size() && choice < 0; ++tile) {
    const auto contexts = consistent_contexts(filled.set, tile, 256);
    for (std::size_t k = 0; k < contexts.size() && choice < 0; ++k)
      if (std::count(contexts[k].begin(), contexts[k].end(), std::uint16_t(tile)) == 1) choice = int(k);
  }
  ASSERT_GE(choice, 0) << "no context without its centre tile around it";
  --tile;
  filled.tiles.assign(filled.set.size(), {});
  filled.tiles[tile] = {TilePoint{0, 0, 0, 1, 0, 1}};
  Mesh mesh;
  add_quad(mesh, float(1.2 * kTile), 0, float(2 * kTile), float(kTile), 0.5f);     // all outside (east)
  add_quad(mesh, float(0.5 * kTile), 0, float(1.5 * kTile), float(kTile), 0.75f);  // straddles the east edge
  add_quad(mesh, float(-kTile), float(-kTile), float(2 * kTile), 0.0f, 0.9f);      // all outside (south)
  const std::vector<Mesh> models{mesh};
  LdiBuildOptions o = small_options();
  o.context_choice = choice;
  const auto ldis = build_tile_ldis(filled, models, o, tile);
  std::size_t straddling = 0;
  for (const LdiImage& ldi : ldis) {
    const LdiView v = ldi.view();
    const double p = v.frame->pixel_size;
    for (int y = 0; y < int(v.frame->height); ++y)
      for (int x = 0; x < int(v.frame->width); ++x)
        for (const DepthPixel& s : v.pixel(x, y)) {
          const auto q = v.position(x, y, s);
          EXPECT_LT(q[0], kTile + p) << "a sample east of the prism";
          EXPECT_GT(q[1], -p) << "a sample south of the prism";
          EXPECT_NEAR(q[2], 0.75, p + 1e-3) << "only the straddling quad reaches into the prism";
          ++straddling;
        }
  }
  EXPECT_GT(straddling, 1000u);
}

// The ground at a point west of a raised plate, with the sun in the east: lit without the plate,
// in its shadow with it; the same ray (same seed) meets the same point in both builds.
TEST(ldi_build, APointInTheSunIsBrighterThanInAShadow) {
  Mesh plate;
  add_quad(plate, 2.4f, 1.4f, 3.0f, 2.6f, 1.0f);
  Mesh nothing = plate;
  nothing.positions.clear();
  nothing.triangles.clear();
  nothing.triangle_material.clear();
  LdiBuildOptions o = small_options();
  o.view.levels = 1;
  o.ground = LdiGround::visible;
  o.shading.shadows = true;
  o.shading.ao_rays = 4;
  o.shading.sun_direction = sun_direction_from_degrees(90, 45);  // east: the shadow falls 1 m west
  auto build = [&](const Mesh& m) {
    const std::vector<Mesh> models{m};
    // The plate model as tall as the plate in both builds, so the prisms (and rays) are the same.
    std::vector<Mesh> with_height = models;
    if (m.positions.empty()) add_quad(with_height[0], 10.0f, 10.0f, 10.1f, 10.1f, 1.0f);
    return build_tile_ldis(one_tile({TilePoint{0, 0, 0, 1, 0, 1}}), with_height, o, 0);
  };
  const auto lit = build(nothing), shadowed = build(plate);
  // Direction 0 looks north: rays stay in x = const planes, so the plate never hides the spot.
  const LdiView a = lit[0].view(), b = shadowed[0].view();
  ASSERT_EQ(a.frame->width, b.frame->width);
  int compared = 0;
  for (int y = 0; y < int(a.frame->height); ++y)
    for (int x = 0; x < int(a.frame->width); ++x) {
      const auto sa = a.pixel(x, y), sb = b.pixel(x, y);
      if (sa.size() != 1 || sb.size() != 1) continue;
      const auto q = a.position(x, y, sa[0]);
      if (std::abs(b.position(x, y, sb[0])[2]) > 0.05) continue;              // the ground in both
      if (!(q[0] > 1.5 && q[0] < 1.9 && q[1] > 1.6 && q[1] < 2.4)) continue;  // well inside the shadow
      EXPECT_EQ(sa[0].depth(), sb[0].depth());
      EXPECT_GT(int(sa[0].r) + sa[0].g + sa[0].b, int(sb[0].r) + sb[0].g + sb[0].b + 60);
      ++compared;
    }
  EXPECT_GT(compared, 5);
}

// cohen8 filled with boxes no wider than the fill's tight radius: sampled in different matching
// contexts, the samples are the same (flowers that cross an edge are the same in every tile with
// that edge color). With shadows and sky light off, the bytes are the same; with them on, the
// geometry (depths, normals, layer counts) still is.
TEST(ldi_build, ResultDoesNotDependOnTheChosenNeighbours) {
  PoissonFillOptions fill;
  fill.points_per_tile = 12;
  fill.seed = 5;
  fill.variants = 1;
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), fill);
  const float r = float(0.7 * filled.radius_tight * kTile);  // corners within the tight radius
  const std::vector<Mesh> models{box(r, 1.2f)};
  for (bool shaded : {false, true}) {
    LdiBuildOptions o = small_options();
    o.view.levels = 1;
    o.shading.shadows = shaded;
    o.shading.ao_rays = shaded ? 4 : 0;
    for (std::size_t tile : {std::size_t{0}, std::size_t{5}}) {
      const auto contexts = consistent_contexts(filled.set, tile, 8);
      ASSERT_GE(contexts.size(), 2u);
      o.context_choice = 0;
      const auto first = build_tile_ldis(filled, models, o, tile);
      for (int choice = 1; choice < int(contexts.size()); ++choice) {
        if (contexts[std::size_t(choice)] == contexts[0]) continue;
        o.context_choice = choice;
        const auto other = build_tile_ldis(filled, models, o, tile);
        ASSERT_EQ(first.size(), other.size());
        for (std::size_t i = 0; i < first.size(); ++i) {
          EXPECT_EQ(first[i].spans, other[i].spans) << "tile " << tile << " context " << choice;
          EXPECT_EQ(first[i].counts, other[i].counts);
          ASSERT_EQ(first[i].depth_pixels.size(), other[i].depth_pixels.size());
          for (std::size_t k = 0; k < first[i].depth_pixels.size(); ++k) {
            const DepthPixel &a = first[i].depth_pixels[k], &b = other[i].depth_pixels[k];
            EXPECT_EQ(a.depth(), b.depth());
            EXPECT_EQ(a.normal(), b.normal());
            if (!shaded) {
              EXPECT_EQ(a, b);
            }
            if (a.depth() != b.depth() || a.normal() != b.normal() || (!shaded && !(a == b))) break;
          }
        }
      }
    }
  }
}

// ---- the pack ----

struct SmallSet {
  FilledTileSet filled;
  std::vector<Mesh> models;
  LdiBuildOptions options;
};
SmallSet small_set() {
  PoissonFillOptions fill;
  fill.points_per_tile = 8;
  fill.seed = 3;
  fill.variants = 2;
  SmallSet s{fill_poisson_tiles(builtin_tileset("cohen8"), fill), {}, small_options()};
  const float r = float(0.7 * s.filled.radius_tight * kTile);
  s.models = {box(r, 1.0f), box(0.6f * r, 1.6f)};
  s.options.view.image_width = 48;
  s.options.ground = LdiGround::visible;
  s.options.shading.shadows = true;
  s.options.shading.ao_rays = 2;
  return s;
}

TEST(ldi_build, PacketsGiveTheSameLdisAsSingleRays) {
  SmallSet s = small_set();
  s.options.view.image_width = 96;
  s.options.packet_width = 1;
  const auto single = build_tile_ldis(s.filled, s.models, s.options, 2);
  for (int width : {4, 8, 16}) {
    s.options.packet_width = width;
    const auto packets = build_tile_ldis(s.filled, s.models, s.options, 2);
    ASSERT_EQ(single.size(), packets.size());
    for (std::size_t i = 0; i < single.size(); ++i) {
      EXPECT_EQ(single[i].spans, packets[i].spans) << "width " << width << " LDI " << i;
      EXPECT_EQ(single[i].counts, packets[i].counts) << "width " << width << " LDI " << i;
      EXPECT_TRUE(single[i].depth_pixels == packets[i].depth_pixels) << "width " << width << " LDI " << i;
    }
  }
}

// Instanced and flattened contexts sample the same surfaces (Embree's float transforms differ a
// little, so the bits may too): the same pixels hold samples, at nearly the same depths.
TEST(ldi_build, InstancedAndFlattenedContextsAgree) {
  SmallSet s = small_set();
  s.options.view.image_width = 96;
  s.options.instancing = true;
  const auto instanced = build_tile_ldis(s.filled, s.models, s.options, 1);
  s.options.instancing = false;
  const auto flat = build_tile_ldis(s.filled, s.models, s.options, 1);
  ASSERT_EQ(instanced.size(), flat.size());
  std::size_t same = 0, all = 0;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const LdiView a = instanced[i].view(), b = flat[i].view();
    for (int y = 0; y < int(a.frame->height); ++y)
      for (int x = 0; x < int(a.frame->width); ++x) {
        const auto pa = a.pixel(x, y), pb = b.pixel(x, y);
        ++all;
        if (pa.size() == pb.size() && (pa.empty() || std::abs(int(pa[0].depth()) - int(pb[0].depth())) <= 2)) ++same;
      }
  }
  EXPECT_GT(double(same), 0.999 * double(all));
}

TEST(ldi_pack, RoundTrips) {
  const SmallSet s = small_set();
  const LdiPackInfo info = ldi_pack_info(s.filled, s.models, s.options);
  std::vector<LdiImage> ldis;
  for (std::size_t t = 0; t < s.filled.tiles.size(); ++t)
    for (LdiImage& ldi : build_tile_ldis(s.filled, s.models, s.options, t)) ldis.push_back(std::move(ldi));
  const fs::path path = scratch("roundtrip.ldi");
  write_ldi_pack(path, info, ldis);
  const LdiPack pack(path);
  EXPECT_EQ(pack.info(), info);
  EXPECT_EQ(pack.info().tiles, 8u);
  for (const LdiImage& ldi : ldis) {
    const LdiView v = pack.ldi(ldi.frame.tile, ldi.frame.level, ldi.frame.direction);
    EXPECT_EQ(std::memcmp(v.frame, &ldi.frame, sizeof(LdiFrame)), 0);
    EXPECT_TRUE(std::equal(v.row_spans.begin(), v.row_spans.end(), ldi.row_spans.begin(), ldi.row_spans.end()));
    EXPECT_TRUE(std::equal(v.spans.begin(), v.spans.end(), ldi.spans.begin(), ldi.spans.end()));
    EXPECT_TRUE(std::equal(v.counts.begin(), v.counts.end(), ldi.counts.begin(), ldi.counts.end()));
    EXPECT_TRUE(
        std::equal(v.depth_pixels.begin(), v.depth_pixels.end(), ldi.depth_pixels.begin(), ldi.depth_pixels.end()));
  }
  // And the builder's own pack holds the same LDIs.
  const fs::path built = scratch("built.ldi");
  build_ldi_pack(s.filled, s.models, s.options, built);
  EXPECT_TRUE(read_bytes(built) == read_bytes(path)) << "build_ldi_pack and write_ldi_pack disagree";
  const LdiPackStats stats = ldi_pack_stats(pack);
  std::uint64_t depth_pixels = 0;
  for (const LdiImage& ldi : ldis) depth_pixels += ldi.depth_pixels.size();
  EXPECT_EQ(stats.depth_pixels, depth_pixels);
  EXPECT_GT(depth_pixels, 0u);
}

TEST(ldi_pack, SameBytesOnOneAndTwoThreads) {
  const SmallSet s = small_set();
  const fs::path one = scratch("one_thread.ldi"), two = scratch("two_threads.ldi");
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    build_ldi_pack(s.filled, s.models, s.options, one);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    build_ldi_pack(s.filled, s.models, s.options, two);
  }
  const std::string a = read_bytes(one), b = read_bytes(two);
  EXPECT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the pack depends on the thread count";
}

class ldi_pack_damage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const SmallSet s = small_set();
    good_ = new fs::path(scratch("good.ldi"));
    build_ldi_pack(s.filled, s.models, s.options, *good_);
  }
  static void TearDownTestSuite() { delete good_; }
  // Writes `bytes` to a file and expects opening it to fail with a message naming the file and `what`.
  static void expect_refused(const std::string& name, const std::string& bytes, const std::string& what) {
    const fs::path path = scratch(name);
    write_bytes(path, bytes);
    try {
      const LdiPack pack(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(what), std::string::npos) << message;
    }
  }
  static inline fs::path* good_ = nullptr;
};

TEST_F(ldi_pack_damage, GoodPackOpens) { EXPECT_NO_THROW(LdiPack{*good_}); }

TEST_F(ldi_pack_damage, TruncatedPacksAreRefused) {
  const std::string bytes = read_bytes(*good_);
  for (std::size_t size :
       {std::size_t{0}, std::size_t{10}, std::size_t{63}, std::size_t{64}, bytes.size() / 2, bytes.size() - 1})
    expect_refused("truncated.ldi", bytes.substr(0, size), "truncated");
}

TEST_F(ldi_pack_damage, BadMagicIsRefused) {
  std::string bytes = read_bytes(*good_);
  bytes[0] = 'X';
  expect_refused("magic.ldi", bytes, "bad magic");
}

TEST_F(ldi_pack_damage, WrongVersionIsRefused) {
  std::string bytes = read_bytes(*good_);
  bytes[8] = char(kLdiPackVersion + 1);
  expect_refused("version.ldi", bytes, "version 2");
}

TEST_F(ldi_pack_damage, OutOfRangeOffsetsAndCountsAreRefused) {
  const std::string good = read_bytes(*good_);
  std::uint64_t index_offset = 0;
  std::memcpy(&index_offset, good.data() + 56, 8);
  auto poke64 = [](std::string& bytes, std::size_t at, std::uint64_t value) {
    std::memcpy(bytes.data() + at, &value, 8);
  };
  auto poke32 = [](std::string& bytes, std::size_t at, std::uint32_t value) {
    std::memcpy(bytes.data() + at, &value, 4);
  };
  std::string bytes = good;
  poke64(bytes, index_offset, std::uint64_t{1} << 40);  // the first LDI far past the end
  expect_refused("offset.ldi", bytes, "outside the data");
  bytes = good;
  poke64(bytes, index_offset + 8, good.size());  // the first LDI's size past the end
  expect_refused("size.ldi", bytes, "outside the data");
  std::uint64_t first = 0;
  std::memcpy(&first, good.data() + index_offset, 8);
  bytes = good;
  poke32(bytes, first + 16, 0xffffffu);  // depth pixel count of the first LDI
  expect_refused("count.ldi", bytes, "LDI (tile 0, level 0, direction 0)");
  bytes = good;
  poke32(bytes, first + 8, 0xffffffu);  // span count
  expect_refused("spans.ldi", bytes, "LDI (tile 0, level 0, direction 0)");
}

// A scene's pack records the light it was shaded with (version 3), so that a folder's readers ask
// the pack; a pack without it (version 2, a bare tile set's) is read as before; a damaged record
// is refused.
TEST_F(ldi_pack_damage, ThePackRecordsItsLightAndAnOlderPackStillOpens) {
  const std::string old_bytes = read_bytes(*good_);
  EXPECT_EQ(std::uint8_t(old_bytes[8]), kLdiPackOldestVersion);
  const LdiPack old(*good_);
  EXPECT_FALSE(old.info().light);
  const SmallSet s = small_set();
  LdiPackInfo info = ldi_pack_info(s.filled, s.models, s.options);
  ShadingSettings light;
  light.ao_rays = 3;
  light.exposure = 1.25f;
  Sun sun;
  sun.strength = 0.7;
  info.light = pack_light_record(light, sun);
  const fs::path path = scratch("lit.ldi");
  build_ldi_pack(s.filled, s.models, s.options, ldi_levels(s.options.view, s.options.tile_size, info.prism_top), info,
                 path);
  const std::string bytes = read_bytes(path);
  EXPECT_EQ(std::uint8_t(bytes[8]), kLdiPackVersion);
  const LdiPack pack(path);
  EXPECT_EQ(pack.info(), info);
  EXPECT_EQ(ldi_pack_stats(pack).depth_pixels, ldi_pack_stats(old).depth_pixels);
  const ShadingSettings back = recorded_light(*pack.info().light);
  EXPECT_EQ(back.ao_rays, 3);
  EXPECT_EQ(back.exposure, 1.25f);
  EXPECT_EQ(with_sun(back, sun).sun_color, with_sun(light, sun).sun_color);
  EXPECT_EQ(with_sun(back, sun).sun_direction, with_sun(light, sun).sun_direction);
  // The record follows the arrays (64 + 12 L + 4 D); its exposure is its 14th number.
  const std::size_t exposure = 64 + 12 * info.levels + 4 * info.directions + 13 * 4;
  std::string damaged = bytes;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(damaged.data() + exposure, &nan, 4);
  expect_refused("light_nan.ldi", damaged, "light: sun strength 0.7, exposure nan");
}

// Every float of a pack is checked on open (issue 25): a NaN fails every comparison, so a NaN tile
// size passed `ldi info` and the view's tile-set check; flipped level and direction arrays passed.
TEST_F(ldi_pack_damage, NonFiniteAndFlippedNumbersAreRefused) {
  const std::string good = read_bytes(*good_);
  const auto poke = [&](std::size_t at, float value) {
    std::string bytes = good;
    std::memcpy(bytes.data() + at, &value, 4);
    return bytes;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const LdiPackInfo info = LdiPack(*good_).info();
  ASSERT_EQ(info.levels, 2u);
  ASSERT_EQ(info.directions, 8u);
  // The header: tile size (32), head height (36), prism top (40), field of view (44).
  expect_refused("tile_nan.ldi", poke(32, nan), "tile size nan: expected meters in (0, 1e6]");
  expect_refused("tile_zero.ldi", poke(32, 0), "tile size 0");
  expect_refused("head_inf.ldi", poke(36, inf), "head height inf");
  expect_refused("top_nan.ldi", poke(40, -nan), "prism top");
  expect_refused("fov.ldi", poke(44, 180), "field of view 180");
  // The arrays after the 64-byte header: 2 resolutions, distances, elevations, then 8 azimuths.
  expect_refused("distance.ldi", poke(64 + 8 + 4, info.level_distances[0] / 2), "level 1: distance");
  expect_refused("elevation.ldi", poke(64 + 16, 95), "level 0: elevation 95");
  expect_refused("elevation_flip.ldi", poke(64 + 16 + 4, info.elevations[0] + 1), "level 1: elevation");
  expect_refused("azimuth_flip.ldi", poke(64 + 24 + 4, 300), "direction 2: azimuth 90");
  expect_refused("azimuth_nan.ldi", poke(64 + 24, nan), "direction 0: azimuth nan");
  // A frame's axes: the origin's x of the first LDI (after 8 32-bit fields).
  std::uint64_t index_offset = 0, first = 0;
  std::memcpy(&index_offset, good.data() + 56, 8);
  std::memcpy(&first, good.data() + index_offset, 8);
  expect_refused("origin.ldi", poke(first + 32, inf), "origin or axes hold a number that is not finite");
}

TEST(ldi_info, JsonStartsWithTheDocumentedKeys) {
  const SmallSet s = small_set();
  const fs::path path = scratch("info.ldi");
  build_ldi_pack(s.filled, s.models, s.options, path);
  const LdiPack pack(path);
  const std::string json = ldi_info_json(pack);
  const std::string head = "{\"tiles\":8,\"levels\":2,\"directions\":8,\"resolutions\":[" +
                           std::to_string(pack.info().resolutions[0]) + "," +
                           std::to_string(pack.info().resolutions[1]) +
                           "],\"depth_pixels\":" + std::to_string(ldi_pack_stats(pack).depth_pixels) +
                           ",\"bytes\":" + std::to_string(pack.file_bytes()) + ",";
  EXPECT_EQ(json.substr(0, head.size()), head);
  const std::string text = ldi_info_text(pack);
  EXPECT_NE(text.find("tiles:        8"), std::string::npos) << text;
  EXPECT_NE(text.find("depth pixels: " + std::to_string(ldi_pack_stats(pack).depth_pixels)), std::string::npos);
}

TEST(ldi_sheet, DrawsLevelsAsRowsAndDirectionsAsColumns) {
  const SmallSet s = small_set();
  const fs::path path = scratch("sheet.ldi");
  build_ldi_pack(s.filled, s.models, s.options, path);
  const LdiPack pack(path);
  const ImageRgb8 sheet = draw_ldi_sheet(pack, 3, 32);
  EXPECT_EQ(sheet.height, 2 * 32);
  EXPECT_EQ(sheet.width, 2 * 8 * 32);
  int lit = 0;
  for (std::size_t i = 0; i < sheet.pixels.size(); ++i) lit += sheet.pixels[i] > 40;
  EXPECT_GT(lit, int(sheet.pixels.size() / 10));
  EXPECT_THROW(draw_ldi_sheet(pack, 8, 32), Error);
}

}  // namespace
}  // namespace wangscape
