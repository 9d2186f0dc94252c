#include "scene/tileset_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "core/atomic_file.h"
#include "exporters/image_io.h"
#include "generator/tiling_preview.h"

namespace wangscape {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_tileset_json_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto path = scratch(name);
  std::ofstream(path) << text;
  return path;
}

// The message of whatever exception `body` throws ("" when none).
template <typename Body>
std::string error_of(Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(TilesetJson, EveryBuiltinSetRoundTripsThroughAFile) {
  for (const std::string& name : builtin_tileset_names()) {
    const TileSet set = builtin_tileset(name);
    const auto path = scratch(name + ".json");
    write_tileset_json(path, set);
    const TileSet back = read_tileset_json(path);
    EXPECT_EQ(back.name, set.name);
    EXPECT_EQ(back.kind, set.kind);
    EXPECT_EQ(back.has_corners, set.has_corners);
    EXPECT_EQ(back.tiles, set.tiles) << name;
    EXPECT_EQ(back.describe(), "tile set '" + path.string() + "'");
  }
}

TEST(TilesetJson, ShapeOfTheDocument) {
  const Json cohen8 = tileset_to_json(builtin_tileset("cohen8"));
  EXPECT_EQ(cohen8["name"], "cohen8");
  EXPECT_EQ(cohen8["kind"], "edge");
  ASSERT_EQ(cohen8["tiles"].size(), 8u);
  EXPECT_EQ(cohen8["tiles"][1].dump(), R"({"n":0,"e":1,"s":1,"w":0})");
  const Json corners = tileset_to_json(builtin_tileset("corner-2"));
  EXPECT_EQ(corners["kind"], "corner");
  EXPECT_EQ(corners["tiles"][1].dump(), R"({"ne":0,"se":0,"sw":0,"nw":1})");
  const Json coded = tileset_to_json(builtin_tileset("cohen8-corners"));
  EXPECT_EQ(coded["kind"], "edge");
  EXPECT_EQ(coded["tiles"][0].size(), 8u);
  // The printed form parses back to the same document.
  EXPECT_EQ(Json::parse(format_tileset_json(coded)), coded);
}

TEST(TilesetJson, ReaderToleratesTileContentsAndOmittedKindAndName) {
  const auto path = write_text("contents.json", R"({"tiles": [
      {"n":0,"e":0,"s":0,"w":0,"points":[[0.1,0.2,3]],"radius_packing":0.05,"radius_tight":0.02,"seed":7},
      {"n":1,"e":1,"s":1,"w":1}], "per_tile": 12})");
  const TileSet set = read_tileset_json(path);
  EXPECT_EQ(set.name, "contents");
  EXPECT_EQ(set.kind, TileKind::edge);
  EXPECT_EQ(set.size(), 2u);
  const TileSet corners = tileset_from_json(Json::parse(R"({"tiles":[{"ne":1,"se":0,"sw":0,"nw":0}]})"), "c.json");
  EXPECT_EQ(corners.kind, TileKind::corner);
}

TEST(TilesetJson, ErrorsNameFileTileKeyAndExpectation) {
  const auto parse = [](const char* text) { return tileset_from_json(Json::parse(text), "x.json"); };
  EXPECT_EQ(error_of([&] { parse(R"({"tiles":[{"n":0,"e":1,"s":1,"w":0},{"n":0,"e":1,"s":1}]})"); }),
            "tile set 'x.json': tile 1: missing key 'w'; every tile of an edge set needs n, e, s, w");
  EXPECT_EQ(error_of([&] { parse(R"({"tiles":[{"n":0,"e":"1","s":1,"w":0}]})"); }),
            "tile set 'x.json': tile 0: key 'e' is \"1\"; expected an integer 0..63");
  EXPECT_EQ(error_of([&] { parse(R"({"tiles":[{"n":0,"e":1,"s":1,"w":-2}]})"); }),
            "tile set 'x.json': tile 0: key 'w' is -2; expected an integer 0..63");
  EXPECT_NE(error_of([&] {
              parse(R"({"tiles":[{"N":0,"e":1,"s":1,"w":0}]})");
            }).find("tile set 'x.json': tile 0: unknown key 'N'"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { parse(R"({"kind":"triangle","tiles":[{"n":0,"e":1,"s":1,"w":0}]})"); }),
            "tile set 'x.json': \"kind\" is \"triangle\"; expected \"edge\" or \"corner\"");
  EXPECT_EQ(error_of([&] { parse(R"({"kind":"corner","tiles":[{"ne":0,"se":1,"sw":1}]})"); }),
            "tile set 'x.json': tile 0: missing key 'nw'; every tile of a corner set needs ne, se, sw, nw");
  EXPECT_EQ(error_of([&] { parse(R"({"tiles":[]})"); }),
            "tile set 'x.json': \"tiles\" is empty; expected a non-empty array of tiles");
  EXPECT_EQ(error_of([&] { parse(R"([1,2])"); }),
            "tile set 'x.json': the document is array; expected an object with \"tiles\"");
  EXPECT_EQ(error_of([&] { parse(R"({"tiles":[{"n":0,"e":1,"s":1,"w":0},{"n":0,"e":1,"s":1,"w":0}]})"); }),
            "tile set 'x.json': tile 1 repeats an earlier tile");
  EXPECT_EQ(
      error_of([&] { parse(R"({"tiles":[{"n":0,"e":1,"s":1,"w":0},{"n":0,"e":1,"s":1,"w":1,"ne":0}]})"); }),
      "tile set 'x.json': tile 1: key 'ne' but tile 0 has no corner colors; every tile must color the same parts");
  const auto bad = write_text("bad.json", "{\"tiles\": [");
  EXPECT_NE(error_of([&] { read_tileset_json(bad); }).find("tile set '" + bad.string() + "': not valid JSON"),
            std::string::npos);
  EXPECT_EQ(error_of([] { read_tileset_json("/nonexistent/x.json"); }),
            "tile set '/nonexistent/x.json': cannot open the file");
}

TEST(TilesetJson, LoadTilesetPicksBuiltinsThenFiles) {
  EXPECT_EQ(load_tileset("cohen12").size(), 12u);
  const auto path = scratch("mine.json");
  write_tileset_json(path, builtin_tileset("owen12"));
  EXPECT_EQ(load_tileset(path.string()).tiles, builtin_tileset("owen12").tiles);
  EXPECT_NE(error_of([] { load_tileset("cohen99"); }).find("unknown tile set 'cohen99'"), std::string::npos);
}

TEST(ImageIo, PngRoundTripsAndFailuresLeaveNoFile) {
  Tiling tiling;
  tiling.width = 7;
  tiling.height = 5;
  for (int t = 0; t < 35; ++t) tiling.tiles.push_back(static_cast<std::uint16_t>(t % 8));
  const ImageRgb8 image = draw_tile_map(tiling, 3);
  const auto path = scratch("map.png");
  write_image(path, image);
  const ImageRgb8 back = read_image(path);
  EXPECT_EQ(back.width, 21);
  EXPECT_EQ(back.height, 15);
  EXPECT_EQ(back.pixels, image.pixels);

  const auto unknown = scratch("map.nosuchformat");
  EXPECT_NE(error_of([&] { write_image(unknown, image); }).find("cannot write '" + unknown.string() + "'"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(unknown));
  EXPECT_THROW(write_image("/nonexistent/dir/map.png", image), Error);
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace wangscape
