// Camera-aware export ([camera_aware]): the near field holds exactly the flowers of the full
// export, nothing the camera cannot see is laid (checked against an independent pinhole
// projection), the proxies are extra variants, the limit counts only what is visible, the keys
// are checked with their lines; interior variation decorrelates copies of a tile.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_file.h"
#include "tests/scene/scene_file_support.h"

namespace wangscape {
namespace {

// A flat 240 m field seen from its southern edge at 1.7 m, the sun low in the west.
std::string field_scene(const std::string& extra, const std::string& tiles_extra = "") {
  return R"(
[terrain]
flat_size = 240.0
[tiles]
tile_size = 4.0
points_per_tile = 10
relaxation_rounds = 0
seed = 3
)" + tiles_extra +
         R"(
[models]
variants = 3
triangle_budget = 600
[camera]
position = [10.0, -110.0, 1.7]
target = [30.0, 0.0, 1.0]
fov = 50.0
[sun]
azimuth = 260.0
elevation = 15.0
[image]
width = 160
height = 90
)" + extra +
         (extra.find("[ground]") == std::string::npos ? "\n[ground]\nbake_pixels = 256\n" : "");
}

Scene scene_of(const std::string& text) { return make_scene(parse_scene_config(text, "test.toml", ".")); }

struct Flower {
  float x, y, z, yaw, scale;
  std::uint16_t variant;
  bool operator<(const Flower& o) const {
    return std::tie(x, y, z, yaw, scale, variant) < std::tie(o.x, o.y, o.z, o.yaw, o.scale, o.variant);
  }
  bool operator==(const Flower& o) const = default;
};

std::vector<Flower> flowers_of(const Scene& scene) {
  std::vector<Flower> out;
  scene.instances([&](const InstanceBatch& b) {
    for (std::size_t k = 0; k < b.size(); ++k)
      out.push_back({b.x[k], b.y[k], b.z[k], b.yaw[k], b.scale[k], b.variant[k]});
  });
  return out;
}

// An independent pinhole camera: where a point falls in the image, in pixels (x right, y down),
// and whether it lies in front of the camera.
struct Pinhole {
  std::array<double, 3> pos, fwd, right, up;
  double focal, width, height;
  explicit Pinhole(const Scene& scene) : pos(scene.camera.position) {
    const auto& t = scene.camera.target;
    fwd = {t[0] - pos[0], t[1] - pos[1], t[2] - pos[2]};
    const double n = std::sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
    for (auto& v : fwd) v /= n;
    const double h = std::hypot(fwd[0], fwd[1]);
    right = {fwd[1] / h, -fwd[0] / h, 0};
    up = {right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2],
          right[0] * fwd[1] - right[1] * fwd[0]};
    width = scene.render.width;
    height = scene.render.height;
    focal = width / 2 / std::tan(scene.camera.fov_degrees * std::numbers::pi / 360);
  }
  // Pixel coordinates, or nothing behind the camera.
  std::optional<std::array<double, 2>> project(double x, double y, double z) const {
    const double d[3] = {x - pos[0], y - pos[1], z - pos[2]};
    const double depth = d[0] * fwd[0] + d[1] * fwd[1] + d[2] * fwd[2];
    if (depth <= 0.01) return std::nullopt;
    const double px = d[0] * right[0] + d[1] * right[1] + d[2] * right[2];
    const double py = d[0] * up[0] + d[1] * up[1] + d[2] * up[2];
    return std::array<double, 2>{width / 2 + focal * px / depth, height / 2 - focal * py / depth};
  }
  bool sees(double x, double y, double z, double margin_pixels = 0) const {
    const auto p = project(x, y, z);
    return p && (*p)[0] >= -margin_pixels && (*p)[0] <= width + margin_pixels && (*p)[1] >= -margin_pixels &&
           (*p)[1] <= height + margin_pixels;
  }
};

TEST(CameraAware, TheNearFieldHoldsExactlyTheFullExportsFlowers) {
  const Scene full = scene_of(field_scene("[camera_aware]\nenabled = false\n"));
  const Scene aware =
      scene_of(field_scene("[camera_aware]\nenabled = true\nnear = 20.0\nfar = 60.0\nsun_margin = 5.0\n"));
  ASSERT_EQ(full.models.size(), 3u);
  ASSERT_EQ(aware.models.size(), 6u);  // three full models, three proxies
  const auto& view = *aware.field->view;
  const Pinhole camera(aware);
  std::vector<Flower> expected, near, proxies;
  for (const Flower& f : flowers_of(full)) {
    const double d = view.distance(f.x, f.y, f.z);
    if (d <= 20 && camera.sees(f.x, f.y, f.z)) expected.push_back(f);
  }
  for (Flower f : flowers_of(aware)) {
    const double d = view.distance(f.x, f.y, f.z);
    EXPECT_LE(d, 60.0 + 1e-3);
    if (f.variant < 3) {
      EXPECT_LE(d, 20.0 + 1e-3);
      if (camera.sees(f.x, f.y, f.z)) near.push_back(f);
    } else {
      EXPECT_GT(d, 20.0 - 1e-3);
      f.variant = static_cast<std::uint16_t>(f.variant - 3);
      proxies.push_back(f);
    }
  }
  ASSERT_GT(expected.size(), 50u);
  std::sort(expected.begin(), expected.end());
  std::sort(near.begin(), near.end());
  EXPECT_EQ(near, expected);  // same positions, variants, poses
  // The proxies are the full export's flowers too, only drawn as the proxy of their variant.
  std::vector<Flower> all = flowers_of(full);
  std::sort(all.begin(), all.end());
  ASSERT_GT(proxies.size(), 100u);
  for (const Flower& f : proxies) EXPECT_TRUE(std::binary_search(all.begin(), all.end(), f));
}

TEST(CameraAware, NothingOutsideTheFrustumPlusMarginIsPlaced) {
  const Scene aware = scene_of(field_scene("[camera_aware]\nnear = 20.0\nfar = 90.0\nsun_margin = 4.0\n"));
  const Pinhole camera(aware);
  const auto& view = *aware.field->view;
  const double s = 4.0, reach = view.options().flower_reach, height = view.options().flower_height;
  // Independently: a flower may stand where its tile, grown by the flowers' reach, height and
  // the sun margin, is seen; a pixel margin of that size at the flower's distance covers it.
  for (const Flower& f : flowers_of(aware)) {
    const double d = view.distance(f.x, f.y, f.z);
    const double margin = camera.focal * (std::sqrt(2.0) * s + reach + height + 4.0) / std::max(d - 10, 1.0);
    EXPECT_TRUE(camera.sees(f.x, f.y, f.z, margin) || d < 12) << f.x << " " << f.y;
  }
  const FieldReport& report = *aware.last_placement;
  EXPECT_EQ(report.visible_tiles + report.culled_tiles, report.field_tiles);
  EXPECT_LE(report.placed_tiles, report.visible_tiles);
  // Tiles whose centre the pinhole sees within far (less a tile) must all be laid; tiles it
  // does not see even with a wide margin must all be culled.
  std::uint64_t surely_seen = 0, maybe_seen = 0;
  for (int j = -30; j < 30; ++j)
    for (int i = -30; i < 30; ++i) {
      const double x = (i + 0.5) * s, y = (j + 0.5) * s;
      const double d = view.distance(x, y, 0);
      if (d < 90 - 2 * s && camera.sees(x, y, 0)) ++surely_seen;
      const double margin = camera.focal * (std::sqrt(2.0) * s + reach + height + 4.0) / std::max(d - 10, 1.0);
      if (d < 90 + 2 * s && (camera.sees(x, y, 0, margin) || d < 12)) ++maybe_seen;
    }
  EXPECT_EQ(report.field_tiles, 3600u);
  EXPECT_GT(surely_seen, 100u);
  EXPECT_GE(report.placed_tiles, surely_seen);
  EXPECT_LE(report.visible_tiles, maybe_seen);
  EXPECT_EQ(report.models + report.proxies, flowers_of(aware).size());
  std::printf("tiles: %llu field, %llu visible (pinhole: %llu surely, %llu at most), %llu placed\n",
              (unsigned long long)report.field_tiles, (unsigned long long)report.visible_tiles,
              (unsigned long long)surely_seen, (unsigned long long)maybe_seen, (unsigned long long)report.placed_tiles);
}

TEST(CameraAware, IsOnWithoutAnAreaAndOffWithOne) {
  EXPECT_TRUE(scene_of(field_scene("")).field->view);
  EXPECT_FALSE(scene_of(field_scene("", "area = [-50.0, -50.0, 50.0, 50.0]\n")).field->view);
  EXPECT_TRUE(
      scene_of(field_scene("[camera_aware]\nenabled = true\n", "area = [-50.0, -50.0, 50.0, 50.0]\n")).field->view);
  // Default distances: a 30 cm head spans 8 pixels at near and one at far (160 px, 50 degrees).
  const Scene scene = scene_of(field_scene(""));  // keeps the view the options belong to alive
  const auto& options = scene.field->view->options();
  EXPECT_NEAR(options.far, 0.3 * 160 / (2 * std::tan(25 * std::numbers::pi / 180)), 1e-9);
  EXPECT_NEAR(options.near, options.far / 8, 1e-9);
  // The sun margin: the tallest flower's shadow at 15 degrees.
  EXPECT_NEAR(options.sun_margin, options.flower_height / std::tan(15 * std::numbers::pi / 180), 1e-9);
}

TEST(CameraAware, TheFieldBeyondFarIsPaintedIntoTheGroundBake) {
  const Scene painted = scene_of(field_scene("[camera_aware]\nnear = 10.0\nfar = 30.0\n"));
  const Scene plain = scene_of(field_scene("[ground]\nbake_pixels = 64\n[camera_aware]\nfar_texture = false\n"));
  ASSERT_TRUE(painted.ground_texture);
  EXPECT_EQ(plain.ground_texture->image.width, 64);
  // Against the same look baked without the field: beyond far the bake changes, near it not.
  const Scene reference = scene_of(field_scene("[camera_aware]\nnear = 10.0\nfar = 30.0\nfar_texture = false\n"));
  const auto& a = painted.ground_texture->image;
  const auto& b = reference.ground_texture->image;
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  const Extent& e = painted.ground_texture->extent;
  const auto& view = *painted.field->view;
  int far_changed = 0, far_pixels = 0, near_changed = 0;
  for (int row = 0; row < a.height; ++row)
    for (int col = 0; col < a.width; ++col) {
      const double x = e.min_x + (col + 0.5) * e.width() / a.width, y = e.max_y - (row + 0.5) * e.height() / a.height;
      const std::size_t o = a.offset(col, row);
      const bool changed = a.pixels[o] != b.pixels[o] || a.pixels[o + 1] != b.pixels[o + 1];
      const double d = view.distance(x, y, 0);
      if (d < 26) near_changed += changed;
      if (d > 31) {
        ++far_pixels;
        far_changed += changed;
      }
    }
  EXPECT_EQ(near_changed, 0);
  EXPECT_GT(far_changed, far_pixels / 3);  // the field's coverage, gaps between the flowers left
}

TEST(CameraAware, TheLimitCountsWhatTheCameraSees) {
  // 9 M tiles of 100 points: 900 million flowers over the ground, a few thousand in view.
  const std::string big = R"(
models = { variants = 2, triangle_budget = 400 }
camera = { position = [0.0, 0.0, 1.7], heading = 0.0 }
image = { width = 64, height = 36 }
ground = { bake_pixels = 64 }
[terrain]
flat_size = 6000.0
[tiles]
tile_size = 2.0
points_per_tile = 100
relaxation_rounds = 0
algorithm = "hash"
set = "complete-edge-2"
)";
  const Scene scene = scene_of(big);
  std::size_t count = 0;
  scene.instances([&](const InstanceBatch& b) { count += b.size(); });
  EXPECT_GT(count, 1000u);
  EXPECT_LT(count, 200000u);
  try {
    scene_of(big + "[camera_aware]\nenabled = false\n");
    FAIL() << "a billion flowers were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("[camera_aware] enabled = true"), std::string::npos) << e.what();
  }
  try {
    scene_of(big + "[camera_aware]\nfar = 5000.0\n");
    FAIL() << "a view of a billion flowers was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:15: 'camera_aware.far' lets the camera see"), std::string::npos)
        << e.what();
  }
}

TEST(CameraAware, KeysAreCheckedWithTheirLines) {
  using scene_file_test::error_of;
  EXPECT_EQ(error_of("[camera_aware]\nfar = 0.0\n"), "test.toml:2: 'camera_aware.far' must be between 0.1 and 1e+06");
  EXPECT_EQ(error_of("[camera_aware]\nnear = -1.0\n"), "test.toml:2: 'camera_aware.near' must be between 0 and 1e+06");
  EXPECT_EQ(error_of("[camera_aware]\nnear = 50.0\nfar = 10.0\n"),
            "test.toml:2: 'camera_aware.near' must not be beyond far");
  EXPECT_EQ(error_of("[camera_aware]\nsun_margin = 1e5\n"),
            "test.toml:2: 'camera_aware.sun_margin' must be between 0 and 10000");
  EXPECT_EQ(error_of("[camera_aware]\nproxy_triangles = 10\n"),
            "test.toml:2: 'camera_aware.proxy_triangles' must be between 400 and 5000000");
  EXPECT_EQ(error_of("[camera_aware]\nenabled = 1\n"), "test.toml:2: 'camera_aware.enabled' must be true or false");
  EXPECT_EQ(error_of("[tiles]\ninterior_variation = \"yes\"\n"),
            "test.toml:2: 'tiles.interior_variation' must be true or false");
  EXPECT_NE(error_of("[camera_aware]\nfar_away = 1.0\n").find("test.toml:2: unknown key 'camera_aware.far_away'"),
            std::string::npos);
}

// The normalized autocorrelation of the variant field at offsets of whole tiles: for each flower,
// the flower nearest to the point `k` tiles east of it; (P[same variant] - sum p_v^2) / (1 - sum p_v^2).
double variant_autocorrelation(const std::vector<Flower>& flowers, double tile, int k, int variants) {
  std::map<std::pair<long, long>, std::vector<const Flower*>> grid;
  for (const Flower& f : flowers) grid[{std::lround(std::floor(f.x)), std::lround(std::floor(f.y))}].push_back(&f);
  std::vector<double> share(static_cast<std::size_t>(variants), 0);
  for (const Flower& f : flowers) share[f.variant] += 1.0 / double(flowers.size());
  double chance = 0;
  for (const double p : share) chance += p * p;
  std::size_t same = 0, pairs = 0;
  for (const Flower& f : flowers) {
    const double tx = f.x + k * tile, ty = f.y;
    const Flower* best = nullptr;
    double best_d = 0.5;  // meters: no partner farther than this
    for (long gy = std::lround(std::floor(ty)) - 1; gy <= std::lround(std::floor(ty)) + 1; ++gy)
      for (long gx = std::lround(std::floor(tx)) - 1; gx <= std::lround(std::floor(tx)) + 1; ++gx) {
        const auto it = grid.find({gx, gy});
        if (it == grid.end()) continue;
        for (const Flower* g : it->second) {
          const double d = std::hypot(g->x - tx, g->y - ty);
          if (d < best_d) best_d = d, best = g;
        }
      }
    if (!best) continue;
    ++pairs;
    same += best->variant == f.variant;
  }
  return (double(same) / double(pairs) - chance) / (1 - chance);
}

TEST(InteriorVariation, DecorrelatesCopiesOfATileAndKeepsThePositions) {
  const std::string area = "area = [-60.0, -60.0, 60.0, 60.0]\n";
  const Scene tiles = scene_of(field_scene("", area));
  const Scene world = scene_of(field_scene("", area + "interior_variation = true\n"));
  auto a = flowers_of(tiles), b = flowers_of(world);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].x, b[k].x);  // positions stay the tiles' Poisson points
    ASSERT_EQ(a[k].y, b[k].y);
  }
  int differ = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differ += a[k].variant != b[k].variant;
  EXPECT_GT(differ, int(a.size()) / 2);
  for (int k = 1; k <= 3; ++k) {
    const double per_tile = variant_autocorrelation(a, 4.0, k, 3), per_world = variant_autocorrelation(b, 4.0, k, 3);
    std::printf("variant autocorrelation at %d tile(s): per tile %.3f, interior variation %.3f\n", k, per_tile,
                per_world);
    EXPECT_GT(per_tile, 0.5);
    EXPECT_LT(std::abs(per_world), 0.1);
  }
}

}  // namespace
}  // namespace wangscape
