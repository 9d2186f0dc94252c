// [[species]] (issue 26): the scene file's species with every key and its errors naming the file,
// line and key; the rules' pieces (density curves, aspect ranges); the meadow built from
// templates/scenes/meadow.toml: three species in its instance stream, every rule holding on
// every placed plant, density following the height, and small plants standing on the mesh.
#include "scene/species.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include "scene/filled_tileset_file.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "tests/scene/scene_file_support.h"

namespace wangscape {
namespace {

using scene_file_test::error_of;
using scene_file_test::parse;

TEST(SpeciesFile, EveryKeyIsRead) {
  const SceneConfig c = parse(R"([[species]]
name = "grass"
density_by_slope = [[10.0, 1.0], [30, 0.5]]

[[species]]
name = "rock"
model = "meshes/boulder.obj"
up_axis = "y"
tight_radius = 0.8
packing_radius = 1.2
share = 0.5
edge_objects = true
min_height = 900.0
max_height = 1200.0
min_slope = 5.0
max_slope = 40.0
aspect = [300.0, 60.0]
mask = "rocks.png"
exclusion = { grass = 1.0 }
density_by_height = [[900.0, 0.2], [1100.0, 1.0]]
)");
  ASSERT_EQ(c.species.size(), 2u);
  const SpeciesConfig& grass = c.species[0];
  EXPECT_EQ(grass.model, "grass");
  EXPECT_TRUE(grass.mesh.empty());
  EXPECT_EQ(grass.variants, 4);
  EXPECT_FALSE(grass.tight_radius);
  EXPECT_EQ(grass.share, 1.0);
  ASSERT_EQ(grass.density_by_slope.size(), 2u);
  EXPECT_EQ(grass.density_by_slope[1][0], 30.0);
  const SpeciesConfig& rock = c.species[1];
  EXPECT_EQ(rock.mesh, std::vector<std::filesystem::path>{"/base/meshes/boulder.obj"});
  EXPECT_TRUE(rock.mesh_y_up);
  EXPECT_EQ(*rock.tight_radius, 0.8);
  EXPECT_EQ(*rock.packing_radius, 1.2);
  EXPECT_EQ(rock.share, 0.5);
  EXPECT_TRUE(rock.edge_objects);
  EXPECT_EQ(*rock.min_height, 900.0);
  EXPECT_EQ(*rock.max_slope, 40.0);
  EXPECT_EQ((*rock.aspect)[0], 300.0);
  EXPECT_EQ(rock.mask, std::filesystem::path("/base/rocks.png"));
  ASSERT_EQ(rock.exclusion.size(), 1u);
  EXPECT_EQ(rock.exclusion[0], (std::pair<std::string, double>{"grass", 1.0}));
  EXPECT_EQ(rock.density_by_height[0][1], 0.2);
  EXPECT_EQ(c.key_lines.at("species.rock.aspect"), 17);
}

TEST(SpeciesFile, BadValuesAreRefusedNamingFileLineAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"model = \"dandelion\"", "test.toml:3: 'species.s.model' 'dandelion' is unknown: expected \"sunflower\""},
      {"tight_radius = 0.0", "test.toml:3: 'species.s.tight_radius' must be between"},
      {"packing_radius = -1.0", "test.toml:3: 'species.s.packing_radius' must be between"},
      {"share = 0", "test.toml:3: 'species.s.share' must be between"},
      {"min_height = 10.0\nmax_height = 5.0", "test.toml:3: 'species.s.min_height' must not be above max_height"},
      {"min_slope = 30.0\nmax_slope = 20.0", "test.toml:3: 'species.s.min_slope' must not be above max_slope"},
      {"max_slope = 95.0", "test.toml:3: 'species.s.max_slope' must be between 0 and 90"},
      {"aspect = [90.0, 90.0]", "test.toml:3: 'species.s.aspect' must be a range"},
      {"aspect = [90.0]", "test.toml:3: 'species.s.aspect' must be an array of 2 numbers"},
      {"exclusion = { t = 1.0 }", "test.toml:3: 'species.s.exclusion' names no species 't'"},
      {"exclusion = { s = 1.0 }", "test.toml:3: 'species.s.exclusion' names its own species 's'"},
      {"exclusion = { s = -1.0 }", "test.toml:3: 'species.s.exclusion' 's' must be meters"},
      {"density_by_height = [[10.0, 1.0], [5.0, 0.5]]",
       "test.toml:3: 'species.s.density_by_height' must have increasing"},
      {"density_by_slope = [[10.0, 1.5]]", "test.toml:3: 'species.s.density_by_slope' holds density 1.5"},
      {"density_by_slope = [10.0, 1.0]", "test.toml:3: 'species.s.density_by_slope' must be an array of [slope"},
      {"model = \"grass\"\ntriangle_budget = 3", "test.toml:4: 'species.s.triangle_budget' must be between 24 and"},
      {"model = \"tree.obj\"\nvariants = 3", "test.toml:4: 'species.s.variants' must be 1 for a mesh file"},
      {"model = \"tree.obj\"\ntriangle_budget = 500", "test.toml:4: 'species.s.triangle_budget' does not apply"},
      {"up_axis = \"y\"", "test.toml:3: 'species.s.up_axis' needs a mesh file"},
      {"colour = 3", "test.toml:3: unknown key 'species.s.colour'"},
  };
  for (const auto& [lines, expected] : cases) {
    const std::string message = error_of(std::string("[[species]]\nname = \"s\"\n") + lines + "\n");
    EXPECT_NE(message.find(expected), std::string::npos) << lines << "\n  gave: " << message;
  }
  EXPECT_NE(error_of("[[species]]\nmodel = \"grass\"\n").find("test.toml:1: 'species' number 1 needs a name"),
            std::string::npos);
  EXPECT_NE(error_of("[[species]]\nname = \"a\"\n[[species]]\nname = \"a\"\n")
                .find("test.toml:4: 'species' name 'a' is given twice"),
            std::string::npos);
  EXPECT_NE(error_of("[models]\nmesh = \"f.obj\"\n[[species]]\nname = \"a\"\n")
                .find("test.toml:2: 'models.mesh' cannot be given with [[species]]"),
            std::string::npos);
}

TEST(SpeciesRules, DensityCurvesArePiecewiseLinearAndFlatBeyondTheEnds) {
  const std::vector<std::array<double, 2>> curve{{100, 0.2}, {200, 1.0}, {300, 0.0}};
  EXPECT_EQ(density_curve_at({}, 5), 1.0);
  EXPECT_EQ(density_curve_at(curve, 0), 0.2);
  EXPECT_DOUBLE_EQ(density_curve_at(curve, 150), 0.6);
  EXPECT_DOUBLE_EQ(density_curve_at(curve, 250), 0.5);
  EXPECT_EQ(density_curve_at(curve, 1000), 0.0);
}

TEST(SpeciesRules, AspectRangesGoClockwiseAndWrapPastNorth) {
  EXPECT_TRUE(aspect_in_range(180, 90, 270));
  EXPECT_FALSE(aspect_in_range(0, 90, 270));
  EXPECT_TRUE(aspect_in_range(10, 300, 60));
  EXPECT_TRUE(aspect_in_range(350, 300, 60));
  EXPECT_FALSE(aspect_in_range(180, 300, 60));
  // A ground falling to the east faces east (90), to the south south (180).
  const double s = std::sin(0.3), c = std::cos(0.3);
  EXPECT_NEAR(aspect_degrees({s, 0, c}), 90, 1e-9);
  EXPECT_NEAR(aspect_degrees({0, -s, c}), 180, 1e-9);
  EXPECT_NEAR(aspect_degrees({-s, s, c}), 315, 1e-9);
}

// A species may be a user mesh: one variant, its species' name on the model, rules as any other.
TEST(Species, AUserMeshIsASpeciesOfOneModel) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_species_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "rock.obj") << "v 0 0 0\nv 0.3 0 0\nv 0 0.3 0\nv 0 0 0.5\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  const SceneConfig c = parse_scene_config(
      "[terrain]\nflat_size = 40.0\n[tiles]\npoints_per_tile = 12\nrelaxation_rounds = 0\narea = [-8.0, -8.0, 8.0, "
      "8.0]\n[[species]]\nname = \"grass\"\nvariants = 2\ntriangle_budget = 100\nshare = 3\n[[species]]\nname = "
      "\"rock\"\nmodel = \"rock.obj\"\nexclusion = { grass = 0.2 }\n",
      "test.toml", dir);
  const Scene scene = make_scene(c);
  ASSERT_EQ(scene.models.size(), 3u);
  EXPECT_EQ(scene.models[2].triangle_count(), 3u);
  EXPECT_EQ(scene.field->species_of_model(2), 1u);
  EXPECT_EQ(scene.field->species_of_model(1), 0u);
  EXPECT_EQ(scene.models[0].materials[0].name, "grass grass");  // named by species
  std::size_t rocks = 0, total = 0;
  scene.instances([&](const InstanceBatch& batch) {
    for (std::size_t k = 0; k < batch.size(); ++k) rocks += batch.variant[k] == 2;
    total += batch.size();
  });
  EXPECT_GT(rocks, 0u);
  EXPECT_GT(total, rocks);
  std::filesystem::remove_all(dir);
}

// A species' painted mask: grass only where the image is white. The mask (a PGM, white west of
// column 691 of 1000) stretched over the DEM's 9660 m puts its edge at about 1838-1848 m east,
// inside the meadow; the dandelions, without a mask, stand on both sides.
TEST(Species, APaintedMaskKeepsItsSpeciesOnTheWhite) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_species_mask_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream pgm(dir / "west.pgm", std::ios::binary);
    pgm << "P5\n1000 10\n255\n";
    for (int row = 0; row < 10; ++row)
      for (int col = 0; col < 1000; ++col) pgm.put(char(col < 691 ? 255 : 0));
  }
  SceneConfig c = load_scene_config(data_root() / "templates/scenes/meadow.toml");
  c.species[0].mask = dir / "west.pgm";
  const Scene scene = make_scene(c);
  double grass_east = -1e9, dandelion_east = -1e9;
  std::size_t grass = 0;
  scene.instances([&](const InstanceBatch& batch) {
    for (std::size_t k = 0; k < batch.size(); ++k) {
      const auto species = scene.field->species_of_model(batch.variant[k]);
      if (species == 0u) {
        grass_east = std::max<double>(grass_east, batch.x[k]);
        ++grass;
      }
      if (species == 1u) dandelion_east = std::max<double>(dandelion_east, batch.x[k]);
    }
  });
  EXPECT_GT(grass, 1000u);
  EXPECT_LT(grass_east, 1849.0);
  EXPECT_GT(dandelion_east, 1880.0);
  std::filesystem::remove_all(dir);
}

// Camera-aware export: each species' proxies follow the full models in the same order, so a
// proxy's species is its full model's, and the stream holds proxies of every species.
TEST(Species, CameraAwareProxiesKeepTheirSpecies) {
  SceneConfig c = load_scene_config(data_root() / "templates/scenes/meadow.toml");
  c.camera_aware.enabled = true;
  c.camera_aware.near = 10;
  c.camera_aware.far = 60;
  const Scene scene = make_scene(c);
  const std::size_t full = scene.field->proxy_offset;
  ASSERT_EQ(full, 16u);
  ASSERT_EQ(scene.models.size(), 2 * full);
  for (std::size_t m = 0; m < full; ++m) {
    // (Independent of species_of_model's own offset: the model's name begins with its species'.)
    const auto species = scene.field->species_of_model(m + full);
    ASSERT_TRUE(species);
    EXPECT_EQ(scene.models[m + full].name.rfind(c.species[*species].name + "_", 0), 0u) << scene.models[m + full].name;
    EXPECT_EQ(scene.models[m + full].name, scene.models[m].name + " proxy");
    EXPECT_LE(scene.models[m + full].triangle_count(), scene.models[m].triangle_count());
  }
  std::map<std::size_t, std::size_t> proxies;
  scene.instances([&](const InstanceBatch& batch) {
    for (std::size_t k = 0; k < batch.size(); ++k)
      if (batch.variant[k] >= full) ++proxies[*scene.field->species_of_model(batch.variant[k])];
  });
  EXPECT_EQ(proxies.size(), 3u);
}

// Radii the tile cannot hold are refused naming the species' key and meters, not the fill's class.
TEST(Species, RadiiTooLargeForTheTileNameTheSpeciesKey) {
  const auto base = [](const char* tile) {
    return std::string("[terrain]\nflat_size = 40.0\n[tiles]\ntile_size = ") + tile + "\n[[species]]\nname = \"g\"\n";
  };
  const std::pair<std::string, std::string> cases[] = {
      {base("2.0") + "tight_radius = 1.5",
       "test.toml:7: 'species.g.tight_radius' is 1.5 m; a tile of 2 m (tiles.tile_size) takes less than 1 m"},
      {base("2.0") + "packing_radius = 1.0", "test.toml:7: 'species.g.packing_radius' is 1 m"},
      // A sunflower reaches out about half a meter: its extent does not fit a 0.8 m tile.
      {base("0.8") + "model = \"sunflower\"\ntriangle_budget = 400", "test.toml:7: 'species.g.model' is 0."},
      // Each radius fits, but the two packing radii plus the exclusion do not: the fill's own
      // check, told by the species' key in meters (the fill said 'tiles.points_per_tile' and
      // 'classes 0 and 1 ... tile sides').
      {base("2.0") + "packing_radius = 0.45\nexclusion = { h = 1.5 }\n[[species]]\nname = \"h\"\npacking_radius = 0.45",
       "test.toml:8: 'species.g.exclusion' keeps 'g' and 'h' 2.4 m apart (their packing radii 0.9 m together, plus "
       "1.5 m); a tile of 2 m (tiles.tile_size) takes less than 2 m"},
      {base("2.0") + "share = 1\n[[species]]\nname = \"h\"\nexclusion = { g = 1.9 }",
       "test.toml:10: 'species.h.exclusion' keeps 'g' and 'h' "},
      // A species too sparse for the tile: its own spacing reaches across it.
      {base("2.0") + "share = 100\n[[species]]\nname = \"h\"\nshare = 0.5",
       "test.toml:10: 'species.h.share' leaves about 0.0995 points of 'h' a tile (its share of "
       "tiles.points_per_tile 20), "},
  };
  for (const auto& [text, expected] : cases) {
    std::string message = "(no error)";
    try {
      make_scene(parse(text + "\n"));
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(expected), std::string::npos) << text << "\n  gave: " << message;
  }
}

// The ground mesh cut onto the bilinear surface: k^2 triangles for each one meeting the area, the
// rest kept; the new vertices on the old edges lie on those straight edges (a DEM cell's edge is
// straight on the bilinear surface too), so no crack opens; a budget too small cuts nothing.
TEST(Species, TheGroundMeshIsCutOntoTheSurfaceWithoutCracks) {
  TerrainConfig terrain;
  terrain.dem = data_root() / "data/SainteHelens.dem";
  terrain.crop = std::array<double, 4>{1700, -5200, 2000, -4900};
  const SceneGround ground = SceneGround::load(terrain);
  const Mesh coarse = ground.mesh();
  const Extent over{1800, -5100, 1860, -5040};
  const auto meets = [&](const std::array<std::uint32_t, 3>& t) {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (std::uint32_t v : t) {
      x0 = std::min<double>(x0, coarse.positions[v][0]);
      x1 = std::max<double>(x1, coarse.positions[v][0]);
      y0 = std::min<double>(y0, coarse.positions[v][1]);
      y1 = std::max<double>(y1, coarse.positions[v][1]);
    }
    return !Extent{x0, y0, x1, y1}.intersected(over).empty();
  };
  std::size_t cut = 0;
  for (const auto& t : coarse.triangles) cut += meets(t);
  ASSERT_GT(cut, 4u);
  Mesh fine = coarse;
  ground.refine_mesh(fine, over, 4);
  EXPECT_EQ(fine.triangles.size(), coarse.triangles.size() + cut * 15);
  EXPECT_EQ(fine.normals.size(), fine.positions.size());
  EXPECT_EQ(fine.triangle_material.size(), fine.triangles.size());
  std::map<std::pair<long, long>, float> height_at;  // new vertices by millimetre position
  for (std::size_t v = coarse.positions.size(); v < fine.positions.size(); ++v)
    height_at[{std::lround(fine.positions[v][0] * 1000), std::lround(fine.positions[v][1] * 1000)}] =
        fine.positions[v][2];
  double worst = 0;
  std::size_t found = 0;
  for (const auto& t : coarse.triangles) {
    if (!meets(t)) continue;
    // The two cell edges (the diagonal, the longest edge, is bent on the bilinear surface, and
    // shared only by the two triangles of its cell, both cut: it opens no crack).
    const auto span = [&](int e) {
      const auto &a = coarse.positions[t[e]], &b = coarse.positions[t[(e + 1) % 3]];
      return std::hypot(b[0] - a[0], b[1] - a[1]);
    };
    const int diagonal = span(0) >= span(1) && span(0) >= span(2) ? 0 : span(1) >= span(2) ? 1 : 2;
    for (int e = 0; e < 3; ++e) {
      if (e == diagonal) continue;
      const auto& a = coarse.positions[t[e]];
      const auto& b = coarse.positions[t[(e + 1) % 3]];
      for (int step = 1; step < 4; ++step) {
        const double u = step / 4.0;
        const auto it = height_at.find(
            {std::lround((a[0] + (b[0] - a[0]) * u) * 1000), std::lround((a[1] + (b[1] - a[1]) * u) * 1000)});
        if (it == height_at.end()) continue;
        ++found;
        worst = std::max(worst, std::abs(it->second - (a[2] + (b[2] - a[2]) * u)));
      }
    }
  }
  EXPECT_GT(found, cut * 4);  // most edge points found (a millimetre grid can miss a rounding)
  EXPECT_LT(worst, 0.01);     // meters: on the straight edge (the interior strays by decimeters)
  Mesh unchanged = coarse;
  ground.refine_mesh(unchanged, over, 8, 10);
  EXPECT_EQ(unchanged.triangles, coarse.triangles);
}

// The far field painted into the ground bake follows the species' rules: where no species grows
// (every one limited below the meadow's lowest ground) nothing is painted, the bake is the bare
// ground's; with the meadow's own rules the far field shows.
TEST(Species, TheFarFieldFollowsTheSpeciesRules) {
  SceneConfig c = load_scene_config(data_root() / "templates/scenes/meadow.toml");
  c.tiles.points_per_tile = 15;  // a quick fill: the test is about painting
  c.tiles.relaxation_rounds = 0;
  c.camera_aware.enabled = true;
  c.camera_aware.near = 5;
  c.camera_aware.far = 20;
  c.ground.emplace().bake_pixels = 1024;  // 9.4 m pixels over the DEM: the meadow spans 13
  const auto bake_of = [](const SceneConfig& config) { return make_scene(config).ground_texture->image.pixels; };
  SceneConfig bare = c;
  bare.camera_aware.far_texture = false;
  SceneConfig nowhere = c;
  for (auto& species : nowhere.species) species.max_height = 900.0;
  const auto ground = bake_of(bare);
  EXPECT_EQ(bake_of(nowhere), ground) << "a far field painted where no species grows";
  EXPECT_NE(bake_of(c), ground) << "the meadow's far field is not painted";
}

// ---- the meadow ----

struct Placed {
  double x, y, z;
  int species;
};

class Meadow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    config_ = new SceneConfig(load_scene_config(data_root() / "templates/scenes/meadow.toml"));
    scene_ = new Scene(make_scene(*config_));
    placed_ = new std::vector<Placed>;
    const FilledTileSet& filled = scene_->field->filled;
    scene_->instances([&](const InstanceBatch& batch) {
      for (std::size_t k = 0; k < batch.size(); ++k) {
        int species = -1;
        for (int s = 0; s < int(config_->species.size()); ++s) {
          const auto [first, count] = class_variant_range(filled, s);
          if (batch.variant[k] >= first && batch.variant[k] < first + count) species = s;
        }
        placed_->push_back({batch.x[k], batch.y[k], batch.z[k], species});
      }
    });
  }
  static void TearDownTestSuite() {
    delete placed_;
    delete scene_;
    delete config_;
  }
  static SceneConfig* config_;
  static Scene* scene_;
  static std::vector<Placed>* placed_;
};
SceneConfig* Meadow::config_ = nullptr;
Scene* Meadow::scene_ = nullptr;
std::vector<Placed>* Meadow::placed_ = nullptr;

TEST_F(Meadow, HasThreeSpeciesAndTheirModelsInOrder) {
  ASSERT_EQ(config_->species.size(), 3u);
  std::map<int, std::size_t> count;
  for (const Placed& p : *placed_) ++count[p.species];
  EXPECT_EQ(count.count(-1), 0u) << "an instance whose variant is no species'";
  for (int s = 0; s < 3; ++s) EXPECT_GT(count[s], 500u) << config_->species[s].name;
  std::size_t models = 0;
  for (int s = 0; s < 3; ++s) {
    const auto [first, variants] = class_variant_range(scene_->field->filled, s);
    EXPECT_EQ(first, int(models));
    EXPECT_EQ(variants, config_->species[s].variants);
    for (int v = first; v < first + variants; ++v)
      EXPECT_EQ(scene_->models[std::size_t(v)].name.rfind(config_->species[s].name + "_", 0), 0u)
          << scene_->models[std::size_t(v)].name;
    models += std::size_t(variants);
  }
  EXPECT_EQ(scene_->models.size(), models);
}

// The folder keeps the filled set as JSON: species, ranks and each class's radii and variants
// come back as they were (a rebuilt folder places the same meadow).
TEST_F(Meadow, FilledSetRoundTripsItsClassesThroughJson) {
  const FilledTileSet& made = scene_->field->filled;
  ASSERT_EQ(made.classes.size(), 3u);
  const FilledTileSet read = filled_tileset_from_json(filled_tileset_to_json(made), "meadow");
  EXPECT_EQ(read.tiles, made.tiles);
  EXPECT_EQ(read.class_variants, made.class_variants);
  ASSERT_EQ(read.classes.size(), 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(read.classes[c].packing, made.classes[c].packing);
    EXPECT_EQ(read.classes[c].tight, made.classes[c].tight);
    EXPECT_EQ(read.classes[c].spacing, made.classes[c].spacing);
  }
}

// Checked here from the ground itself (height, slope, normal), not through SpeciesRules.
TEST_F(Meadow, EveryRuleHoldsOnEveryPlacedPlant) {
  const SceneGround& ground = scene_->field->ground;
  std::size_t checked = 0;
  for (const Placed& p : *placed_) {
    ASSERT_GE(p.species, 0);
    const SpeciesConfig& c = config_->species[std::size_t(p.species)];
    SCOPED_TRACE(c.name);
    if (c.max_height) {
      EXPECT_LE(p.z, *c.max_height + 1e-3);
    }
    if (c.min_height) {
      EXPECT_GE(p.z, *c.min_height - 1e-3);
    }
    if (c.max_slope) {
      EXPECT_LE(*ground.slope_degrees(p.x, p.y), *c.max_slope + 0.01);
    }
    if (c.aspect) {
      const auto n = *ground.normal(p.x, p.y);
      const double compass = std::fmod(std::atan2(n[0], n[1]) * 180 / std::numbers::pi + 360, 360);
      const double from = (*c.aspect)[0], span = std::fmod((*c.aspect)[1] - from + 360, 360);
      if (n[2] < std::cos(std::numbers::pi / 180)) {
        EXPECT_LE(std::fmod(compass - from + 360, 360), span + 0.01);
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 10000u);
  // The rules bind: some of each ruled species' ground is refused (the meadow is not all of it).
  std::map<int, double> highest;
  for (const Placed& p : *placed_) highest[p.species] = std::max(highest[p.species], p.z);
  EXPECT_LT(highest[2], highest[0] - 5) << "sunflowers reach as high as grass: max_height does not bind";
}

// density_by_height: dandelions stand thinner on the low ground (0.3 at 995 m) than on the top.
TEST_F(Meadow, DensityFollowsTheHeight) {
  std::size_t low[2] = {0, 0}, high[2] = {0, 0};  // grass, dandelion
  for (const Placed& p : *placed_) {
    if (p.species > 1) continue;
    if (p.z < 997) ++low[p.species];
    if (p.z > 1012) ++high[p.species];
  }
  ASSERT_GT(low[0], 200u);
  ASSERT_GT(high[0], 200u);
  // Per grass clump (which has no height rule) to cancel the areas' sizes and slopes.
  const double low_ratio = double(low[1]) / double(low[0]), high_ratio = double(high[1]) / double(high[0]);
  EXPECT_LT(low_ratio, 0.6 * high_ratio) << low_ratio << " vs " << high_ratio;
}

// Small plants stand on the mesh the renderers draw: the terrain mesh under the field follows
// the bilinear ground within 2 cm at every plant (it strayed by decimeters per DEM cell).
TEST_F(Meadow, PlantsStandOnTheTerrainMesh) {
  const Mesh& terrain = scene_->terrain;
  // The mesh's height at (x, y): the triangle containing it (brute force over the field's).
  std::vector<std::size_t> under;
  const Extent area = scene_->field_area;
  for (std::size_t t = 0; t < terrain.triangles.size(); ++t) {
    const auto& p = terrain.positions[terrain.triangles[t][0]];
    if (p[0] > area.min_x - 40 && p[0] < area.max_x + 40 && p[1] > area.min_y - 40 && p[1] < area.max_y + 40)
      under.push_back(t);
  }
  double worst = 0;
  for (std::size_t k = 0; k < placed_->size(); k += 97) {
    const Placed& p = (*placed_)[k];
    for (std::size_t t : under) {
      const auto& a = terrain.positions[terrain.triangles[t][0]];
      const auto& b = terrain.positions[terrain.triangles[t][1]];
      const auto& c = terrain.positions[terrain.triangles[t][2]];
      const double d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
      const double wa = ((b[1] - c[1]) * (p.x - c[0]) + (c[0] - b[0]) * (p.y - c[1])) / d;
      const double wb = ((c[1] - a[1]) * (p.x - c[0]) + (a[0] - c[0]) * (p.y - c[1])) / d;
      const double wc = 1 - wa - wb;
      if (wa < -1e-6 || wb < -1e-6 || wc < -1e-6) continue;
      worst = std::max(worst, std::abs(wa * a[2] + wb * b[2] + wc * c[2] - p.z));
      break;
    }
  }
  EXPECT_LT(worst, 0.02);
}

}  // namespace
}  // namespace wangscape
