// The POV-Ray exporter and runner against the real POV-Ray: tiny scenes render, the image
// shows the flowers (a band of sunflower-yellow pixels), every exporter option parses, and
// failures are reported with POV-Ray's own words.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "exporters/povray_writer.h"
#include "renders/external/child_process.h"
#include "renders/external/povray_render.h"
#include "scene/wind.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

// A box from (x0,y0,z0) to (x1,y1,z1) with one material, appended to `mesh`.
void add_box(Mesh& mesh, std::array<float, 3> lo, std::array<float, 3> hi, std::uint16_t material) {
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i < 8; ++i) {
    const std::array<float, 3> p{(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]};
    mesh.positions.push_back(p);
    const float cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2, cz = (lo[2] + hi[2]) / 2;
    std::array<float, 3> n{p[0] - cx, p[1] - cy, p[2] - cz};
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    mesh.normals.push_back({n[0] / len, n[1] / len, n[2] / len});
  }
  const std::uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
    mesh.triangle_material.push_back(material);
  }
}

// A stand-in flower: a green stem and a big yellow head, about 1.6 m tall.
Mesh test_flower(float head_size) {
  Mesh mesh;
  mesh.name = "test flower";
  mesh.materials = {{"petal", {0.95f, 0.65f, 0.02f}, 0.6f, 0.3f}, {"stem", {0.1f, 0.35f, 0.05f}, 0.8f, 0.2f}};
  add_box(mesh, {-0.03f, -0.03f, 0.0f}, {0.03f, 0.03f, 1.5f}, 1);
  add_box(mesh, {0.0f, -head_size, 1.5f - head_size}, {0.08f, head_size, 1.5f + head_size}, 0);
  return mesh;
}

Mesh flat_terrain(float size, int cells) {
  Mesh mesh;
  mesh.name = "flat terrain";
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      mesh.positions.push_back(
          {size * float(i) / float(cells) - size / 2, size * float(j) / float(cells) - size / 2, 0.0f});
      mesh.normals.push_back({0, 0, 1});
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const auto a = std::uint32_t(j * (cells + 1) + i), b = a + 1, c = a + std::uint32_t(cells + 1), d = c + 1;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  return mesh;
}

// A 10 x 10 grid of flowers, 1 m apart, seen across from the south-west.
Scene tiny_scene(bool with_instances = true) {
  Scene scene;
  scene.name = "povray test";
  scene.terrain = flat_terrain(400, 8);
  scene.models = {test_flower(0.25f), test_flower(0.3f)};
  if (with_instances) {
    scene.instances = [](const std::function<void(const InstanceBatch&)>& sink) {
      InstanceBatch batch;
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 10; ++i)
          batch.push_back(float(i), float(j), 0.0f, float(std::numbers::pi / 4), 1.0f, std::uint16_t((i + j) % 2), 0);
      sink(batch);
    };
  }
  scene.camera.position = {-6, -6, 2.5};
  scene.camera.target = {5, 5, 1.0};
  scene.camera.fov_degrees = 60;
  scene.sun = {200, 40, 1.0};
  scene.render.width = 96;
  scene.render.height = 72;
  scene.render.threads = 2;
  scene.georeference = {{"origin_latitude", "46.2"}, {"origin_longitude", "-122.18"}};
  return scene;
}

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("wangscape_povray_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

struct PixelStats {
  double yellow_fraction = 0;
  double luminance_spread = 0;  // standard deviation of luminance, 0..1
};

PixelStats measure(const fs::path& png) {
  auto in = OIIO::ImageInput::open(png.string());
  EXPECT_TRUE(in) << "cannot open " << png;
  if (!in) return {};
  const auto& spec = in->spec();
  std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  PixelStats stats;
  double sum = 0, sum2 = 0;
  std::size_t yellow = 0, count = std::size_t(spec.width) * std::size_t(spec.height);
  for (std::size_t p = 0; p < count; ++p) {
    const float r = pixels[p * std::size_t(spec.nchannels)], g = pixels[p * std::size_t(spec.nchannels) + 1],
                b = pixels[p * std::size_t(spec.nchannels) + 2];
    // Sunflower yellow (sRGB): bright red and green, little blue.
    if (r > 0.45f && g > 0.28f && b < 0.5f * g && r > 1.2f * b + 0.25f) ++yellow;
    const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    sum += y;
    sum2 += y * y;
  }
  stats.yellow_fraction = double(yellow) / double(count);
  const double mean = sum / double(count);
  stats.luminance_spread = std::sqrt(std::max(0.0, sum2 / double(count) - mean * mean));
  return stats;
}

TEST(PovrayRender, TinySceneRendersFlowersInABand) {
  const auto dir = scratch("tiny");
  write_povray_scene(tiny_scene(), dir);
  const auto result = render_povray(dir);
  ASSERT_TRUE(fs::exists(result.image));
  EXPECT_TRUE(fs::exists(dir / "povray.log"));
  const auto stats = measure(result.image);
  EXPECT_GT(stats.luminance_spread, 0.03) << "the image is blank";
  EXPECT_GT(stats.yellow_fraction, 0.02) << "the flowers vanished";
  EXPECT_LT(stats.yellow_fraction, 0.6) << "the flowers fill the frame";
}

TEST(PovrayRender, WithoutInstancesNoYellow) {
  // The yellow band above can fail: the same view without flowers has no yellow at all.
  const auto dir = scratch("empty");
  write_povray_scene(tiny_scene(false), dir);
  const auto stats = measure(render_povray(dir).image);
  EXPECT_LT(stats.yellow_fraction, 0.002);
  EXPECT_GT(stats.luminance_spread, 0.03);
}

TEST(PovrayRender, SizeOverrideChangesTheImage) {
  const auto dir = scratch("size");
  write_povray_scene(tiny_scene(), dir);
  PovrayRenderOptions options;
  options.width = 40;
  options.height = 30;
  const auto result = render_povray(dir, options);
  auto in = OIIO::ImageInput::open(result.image.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 40);
  EXPECT_EQ(in->spec().height, 30);
}

// Every exporter option gives a scene POV-Ray parses and renders without error.
TEST(PovrayRender, EveryOptionParses) {
  struct Variant {
    const char* name;
    std::function<void(Scene&)> apply;
  };
  const std::vector<Variant> variants = {
      {"radiosity", [](Scene& s) { s.render.radiosity = true; }},
      {"antialias", [](Scene& s) { s.render.antialias_samples = 3; }},
      {"no_terrain", [](Scene& s) { s.terrain = Mesh{}; }},
      {"one_material_no_normals",
       [](Scene& s) {
         for (auto& m : s.models) {
           m.materials.resize(1);
           m.triangle_material.assign(m.triangles.size(), 0);
           m.normals.clear();
         }
       }},
      {"no_materials", [](Scene& s) { s.models[0].materials.clear(); }},
      {"low_sun_no_georeference",
       [](Scene& s) {
         s.sun = {90, 3, 0.5};
         s.georeference.clear();
       }},
  };
  for (const auto& variant : variants) {
    SCOPED_TRACE(variant.name);
    auto scene = tiny_scene();
    variant.apply(scene);
    scene.render.width = 32;
    scene.render.height = 24;
    const auto dir = scratch(variant.name);
    write_povray_scene(scene, dir);
    EXPECT_NO_THROW(render_povray(dir));
    EXPECT_TRUE(fs::exists(dir / "render.png"));
  }
}

TEST(PovrayRender, FailureQuotesPovrayAndLeavesNoImage) {
  const auto dir = scratch("broken");
  write_povray_scene(tiny_scene(), dir);
  std::ofstream(dir / "models.inc", std::ios::app) << "\nthis_is_not_pov_syntax {\n";
  try {
    render_povray(dir);
    FAIL() << "a broken scene rendered";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("POV-Ray exited"), std::string::npos) << message;
    EXPECT_NE(message.find("models.inc"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(dir / "render.png"));
  EXPECT_TRUE(fs::exists(dir / "povray.log"));
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos);
}

TEST(PovrayRender, MissingPovrayIsNamed) {
  const auto dir = scratch("missing");
  write_povray_scene(tiny_scene(), dir);
  PovrayRenderOptions options;
  options.executable = "povray-that-does-not-exist";
  try {
    render_povray(dir, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("povray-that-does-not-exist"), std::string::npos) << e.what();
  }
}

TEST(PovrayRender, FolderWithoutSceneIsAnError) {
  const auto dir = scratch("nothing");
  EXPECT_THROW(render_povray(dir), Error);
}

// The wind's functions as POV-Ray itself evaluates them equal the lean every other engine takes
// (WindField::lean), at random places and times over many winds. (POV-Ray 3.7 folds
// `- a * Wind_Time + b` in a function into -(a * t + b): the first version of these functions
// leaned every plant wrong in POV-Ray alone, which this test catches.)
TEST(PovrayRender, WindFunctionsLeanAsEveryEngine) {
  const auto dir = scratch("wind");
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> direction(0, 360), strength(1, 45), scale(0.5, 60), speed(0, 20);
  std::uniform_real_distribution<double> place(-9000, 9000), time(0, 300);
  struct Probe {
    WindField field;
    double e, n, t;
  };
  std::vector<Probe> probes;
  std::string pov = "#version 3.7;\n";
  for (int wind = 0; wind < 12; ++wind) {
    const WindField field = wind_field({direction(rng), strength(rng), scale(rng), speed(rng)});
    for (int k = 0; k < 5; ++k) {
      const Probe probe{field, place(rng), place(rng), time(rng)};
      // Each probe with its own time: the functions compiled anew after Wind_Time changes.
      if (!probes.empty()) pov += "#undef Wind_East\n#undef Wind_North\n";  // functions cannot be redeclared
      pov += "#declare Wind_Time = " + std::to_string(probe.t) + ";\n" + povray_wind_functions(field);
      pov += "#debug concat(\"lean \", str(Wind_East(" + std::to_string(probe.e) + ", " + std::to_string(probe.n) +
             "), 0, 9), \" \", str(Wind_North(" + std::to_string(probe.e) + ", " + std::to_string(probe.n) +
             "), 0, 9), \"\\n\")\n";
      probes.push_back(probe);
    }
  }
  std::ofstream(dir / "wind.pov") << pov;
  const fs::path povray = find_program("povray");
  ASSERT_FALSE(povray.empty()) << "povray is not on PATH";
  const ChildExit exit =
      run_logged({povray.string(), "+Iwind.pov", "-D", "+W1", "+H1", "+O/dev/null"}, dir / "log", dir);
  ASSERT_TRUE(exit.exited && exit.status == 0) << exit.describe() << last_log_lines(dir / "log", 10);
  std::ifstream log(dir / "log");
  std::size_t seen = 0;
  for (std::string line; std::getline(log, line);) {
    if (!line.starts_with("lean ")) continue;
    ASSERT_LT(seen, probes.size());
    const Probe& p = probes[seen++];
    // The probe's time and place as the .pov spells them (six decimals).
    const auto six = [](double v) { return std::stod(std::to_string(v)); };
    const WindLean expected = p.field.lean(six(p.e), six(p.n), six(p.t));
    std::istringstream words(line.substr(5));
    double east = 0, north = 0;
    words >> east >> north;
    EXPECT_NEAR(east, expected.east, 1e-6) << "probe " << seen - 1;
    EXPECT_NEAR(north, expected.north, 1e-6) << "probe " << seen - 1;
  }
  EXPECT_EQ(seen, probes.size());
}

}  // namespace
}  // namespace wangscape
