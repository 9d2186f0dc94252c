#include "generator/tileset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "generator/tiling_preview.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

using testing::error_of;

TEST(TileSet, BuiltinSizes) {
  const std::map<std::string, std::size_t> sizes = {{"cohen8", 8},           {"cohen12", 12},
                                                    {"cohen18", 18},         {"owen12", 12},
                                                    {"complete-edge-2", 16}, {"complete-edge-3", 81},
                                                    {"corner-2", 16},        {"corner-4", 256},
                                                    {"cohen8-corners", 64},  {"cohen8-corners-full", 128}};
  for (const auto& [name, size] : sizes) {
    EXPECT_TRUE(is_builtin_tileset(name));
    EXPECT_EQ(builtin_tileset(name).size(), size) << name;
  }
  const TileSet corners = builtin_tileset("corner-3");
  EXPECT_EQ(corners.kind, TileKind::corner);
  EXPECT_FALSE(corners.has_edges);
  EXPECT_EQ(corners.corner_colors, 3);
  const TileSet cohen12 = builtin_tileset("cohen12");
  EXPECT_EQ(cohen12.horizontal_colors, 2);
  EXPECT_EQ(cohen12.vertical_colors, 3);
}

TEST(TileSet, Cohen8IsTheEvenParitySetWithTwoTilesPerNorthWestAndSouthEastPair) {
  const TileSet set = builtin_tileset("cohen8");
  std::map<std::pair<int, int>, int> north_west, south_east;
  for (const Tile& t : set.tiles) {
    EXPECT_EQ((t.n() + t.e() + t.s() + t.w()) % 2, 0);
    ++north_west[{t.n(), t.w()}];
    ++south_east[{t.s(), t.e()}];
  }
  EXPECT_EQ(north_west.size(), 4u);
  EXPECT_EQ(south_east.size(), 4u);
  for (const auto& [pair, count] : north_west) EXPECT_EQ(count, 2);
  for (const auto& [pair, count] : south_east) EXPECT_EQ(count, 2);
}

TEST(TileSet, Owen12IsTheTableOfTheOwenWriteUp) {
  const TileSet set = builtin_tileset("owen12");
  const char* table[] = {"0312", "1302", "0203", "1013", "0310", "1200",
                         "0012", "0002", "1003", "0213", "1210", "1300"};
  for (std::size_t t = 0; t < 12; ++t) {
    const Tile& tile = set.tiles[t];
    const std::string nesw = {char('0' + tile.n()), char('0' + tile.e()), char('0' + tile.s()), char('0' + tile.w())};
    EXPECT_EQ(nesw, table[t]) << "tile " << t;
  }
}

TEST(TileSet, CornerCodedSetsStayStochasticForTheThreeConstrainedCorners) {
  // Reduced set: for each N, W edge pair and NE, SW, NW coding, two tiles to choose from.
  const TileSet set = builtin_tileset("cohen8-corners");
  std::map<std::array<int, 5>, int> choices;
  for (const Tile& t : set.tiles) ++choices[{t.n(), t.w(), t.ne(), t.sw(), t.nw()}];
  EXPECT_EQ(choices.size(), 32u);
  for (const auto& [key, count] : choices) EXPECT_EQ(count, 2);
  // Full set: every corner coding of every cohen8 tile.
  const TileSet full = builtin_tileset("cohen8-corners-full");
  std::map<std::array<int, 4>, int> codings;
  for (const Tile& t : full.tiles) ++codings[{t.n(), t.e(), t.s(), t.w()}];
  EXPECT_EQ(codings.size(), 8u);
  for (const auto& [edges, count] : codings) EXPECT_EQ(count, 16);
}

TEST(TileSet, MakeTilesetErrorsNameTheSourceAndTile) {
  EXPECT_EQ(error_of([] {
              make_tileset("x", {Tile::edges(0, 1, 0, 1), Tile::edges(0, 1, 0, 1)}, "x.json");
            }),
            "tile set 'x.json': tile 1 repeats an earlier tile");
  EXPECT_EQ(error_of([] { make_tileset("x", {Tile::edges(0, 1, 64, 1)}, "x.json"); }),
            "tile set 'x.json': tile 0 has color 64 at s; expected 0..63");
  EXPECT_EQ(error_of([] { make_tileset("x", {}, "x.json"); }), "tile set 'x.json': no tiles");
  EXPECT_NE(error_of([] { builtin_tileset("cohen9"); }).find("unknown tile set 'cohen9'"), std::string::npos);
  EXPECT_FALSE(is_builtin_tileset("complete-edge-9"));
  EXPECT_EQ(builtin_tileset("cohen8").describe(), "tile set 'cohen8'");
}

TEST(TilingPreview, TileMapHasOneBlockPerTileWithNorthUp) {
  Tiling tiling;
  tiling.width = 3;
  tiling.height = 2;
  tiling.tiles = {0, 1, 2, 3, 4, 5};  // southern row 0 1 2, northern row 3 4 5
  const ImageRgb8 image = draw_tile_map(tiling, 5);
  ASSERT_EQ(image.width, 15);
  ASSERT_EQ(image.height, 10);
  EXPECT_EQ(image.at(0, 0), tile_pseudo_color(3));
  EXPECT_EQ(image.at(14, 9), tile_pseudo_color(2));
  EXPECT_EQ(image.at(7, 7), tile_pseudo_color(1));
  for (std::size_t a = 0; a < 16; ++a)
    for (std::size_t b = a + 1; b < 16; ++b) EXPECT_NE(tile_pseudo_color(a), tile_pseudo_color(b)) << a << " " << b;
  EXPECT_THROW(draw_tile_map(tiling, 0), Error);
}

TEST(TilingPreview, SheetDrawsEdgeTrianglesAndCornerQuadrants) {
  const TileSet edges = builtin_tileset("cohen8");
  const ImageRgb8 sheet = draw_tileset_sheet(edges, 40);
  // 8 tiles: 3 columns, 3 rows of 40 px plus 5 px gaps.
  EXPECT_EQ(sheet.width, 3 * 45 + 5);
  EXPECT_EQ(sheet.height, 3 * 45 + 5);
  // Tiles whose N colors differ show different colors at the top middle.
  const auto top_middle = [&](int t) { return sheet.at(5 + (t % 3) * 45 + 20, 5 + (t / 3) * 45 + 2); };
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      EXPECT_EQ(top_middle(a) == top_middle(b), edges.tiles[a].n() == edges.tiles[b].n()) << a << " " << b;

  const TileSet corners = builtin_tileset("corner-2");
  const ImageRgb8 corner_sheet = draw_tileset_sheet(corners, 40);
  const auto quadrant = [&](int t, int dx, int dy) {
    return corner_sheet.at(5 + (t % 4) * 45 + dx, 5 + (t / 4) * 45 + dy);
  };
  for (int t = 0; t < 16; ++t) {
    const Tile& tile = corners.tiles[t];
    EXPECT_EQ(quadrant(t, 35, 5) == quadrant(t, 5, 35), tile.ne() == tile.sw()) << t;
    EXPECT_EQ(quadrant(t, 5, 5) == quadrant(t, 35, 35), tile.nw() == tile.se()) << t;
  }
}

}  // namespace
}  // namespace wangscape
