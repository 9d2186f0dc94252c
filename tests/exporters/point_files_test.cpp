// Filled tile-set JSON round trip, and the CSV / PLY point writer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "exporters/point_writer.h"
#include "scene/filled_tileset_file.h"

namespace wangscape {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_point_files_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FilledTilesetJson, RoundTripsEveryPointExactly) {
  for (const char* name : {"cohen8", "corner-2", "cohen8-corners"}) {
    PoissonFillOptions options;
    options.points_per_tile = 8;
    options.relax_rounds = 5;
    options.seed = 17;
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), options);
    const auto path = scratch(std::string(name) + ".json");
    write_filled_tileset_json(path, filled);
    const FilledTileSet back = read_filled_tileset_json(path);
    EXPECT_EQ(back.set.tiles, filled.set.tiles);
    EXPECT_EQ(back.seed, filled.seed);
    EXPECT_EQ(back.radius_packing, filled.radius_packing);
    EXPECT_EQ(back.radius_tight, filled.radius_tight);
    EXPECT_EQ(back.variants, filled.variants);
    EXPECT_EQ(back.tiles, filled.tiles) << name;
    // Still a plain tile set for the color readers.
    EXPECT_EQ(read_tileset_json(path).tiles, filled.set.tiles);
  }
}

TEST(FilledTilesetJson, NamesTheTileAndPointAtFault) {
  PoissonFillOptions options;
  options.points_per_tile = 4;
  Json doc = filled_tileset_to_json(fill_poisson_tiles(builtin_tileset("cohen8"), options));
  doc["tiles"][2]["points"][0]["x"] = 1.5;
  try {
    filled_tileset_from_json(doc, "bad.json");
    FAIL() << "accepted x = 1.5";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'bad.json': tile 2 point 0: \"x\""), std::string::npos) << e.what();
  }
  Json plain = tileset_to_json(builtin_tileset("cohen8"));
  EXPECT_THROW(filled_tileset_from_json(plain, "plain.json"), Error);
}

// Found by fuzz/filled_tileset_fuzz (fuzz/corpus/filled_tileset/regress-x-rounds-to-one.json): a
// value in range as text but out of range as the float kept was accepted, written back as 1.0
// and then refused. Every float key is checked as kept; an accepted set re-reads as it was.
TEST(FilledTilesetJson, RangesHoldForTheFloatsKept) {
  PoissonFillOptions options;
  options.points_per_tile = 3;
  const Json good = filled_tileset_to_json(fill_poisson_tiles(builtin_tileset("cohen8"), options));
  const struct {
    const char* key;
    double value;
  } cases[] = {{"x", 0.99999999}, {"y", 0.99999999}, {"scale", 1e-6}, {"yaw", 6.99999999}};
  for (const auto& c : cases) {
    Json doc = good;
    doc["tiles"][1]["points"][0][c.key] = c.value;
    try {
      const FilledTileSet accepted = filled_tileset_from_json(doc, "edge.json");
      EXPECT_EQ(filled_tileset_from_json(filled_tileset_to_json(accepted), "rewritten.json").tiles, accepted.tiles)
          << c.key;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("tile 1 point 0: \"" + std::string(c.key) + "\""), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("as a float"), std::string::npos) << e.what();
    }
  }
  Json rounded = good;
  rounded["tiles"][1]["points"][0]["x"] = 0.99999999;
  EXPECT_THROW(filled_tileset_from_json(rounded, "x.json"), Error);
}

InstanceBatch sample_batch() {
  InstanceBatch b;
  b.push_back(1.5f, -2.25f, 100.125f, 0.5f, 1.0f, 3, 7);
  b.push_back(0.1f, 1e6f, -3.0f, 6.25f, 0.875f, 0, 0);
  return b;
}

TEST(PointWriter, CsvHasTheHeaderAndShortestNumbers) {
  const auto path = scratch("points.csv");
  PointWriter writer(path);
  writer.write(sample_batch());
  writer.write(sample_batch());
  EXPECT_FALSE(std::filesystem::exists(path)) << "nothing at the path before commit";
  writer.commit();
  EXPECT_EQ(writer.count(), 4u);
  EXPECT_EQ(slurp(path),
            "x,y,z,variant,yaw,scale,tile\n"
            "1.5,-2.25,100.125,3,0.5,1,7\n"
            "0.1,1e+06,-3,0,6.25,0.875,0\n"
            "1.5,-2.25,100.125,3,0.5,1,7\n"
            "0.1,1e+06,-3,0,6.25,0.875,0\n");
}

TEST(PointWriter, PlyHeaderCountsTheVerticesAndBodyIsLittleEndian) {
  const auto path = scratch("points.ply");
  {
    PointWriter writer(path);
    writer.write(sample_batch());
    writer.commit();
  }
  const std::string data = slurp(path);
  const auto end = data.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = data.substr(0, end);
  EXPECT_NE(header.find("format binary_little_endian 1.0\n"), std::string::npos);
  std::istringstream lines(header);
  std::string line;
  long count = -1;
  while (std::getline(lines, line))
    if (line.rfind("element vertex", 0) == 0) count = std::stol(line.substr(15));
  EXPECT_EQ(count, 2);
  const std::size_t body = end + 11;
  ASSERT_EQ(data.size() - body, 2u * 26u);
  float x = 0;
  std::uint16_t variant = 0;
  std::uint32_t tile = 0;
  std::memcpy(&x, data.data() + body, 4);
  std::memcpy(&variant, data.data() + body + 12, 2);
  std::memcpy(&tile, data.data() + body + 22, 4);
  EXPECT_EQ(x, 1.5f);
  EXPECT_EQ(variant, 3);
  EXPECT_EQ(tile, 7u);
}

TEST(PointWriter, UncommittedWriterLeavesNoFile) {
  const auto path = scratch("abandoned.csv");
  {
    PointWriter writer(path);
    writer.write(sample_batch());
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace wangscape
