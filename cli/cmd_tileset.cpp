// wangscape tileset --set NAME|FILE [--json] [--sheet sheet.png]: print or draw a tile set.
#include <fmt/core.h>

#include <memory>

#include "cli/command.h"
#include "exporters/image_io.h"
#include "exporters/tileset_json.h"
#include "generator/tiling_preview.h"

namespace wangscape::cli {

namespace {

struct TilesetOptions {
  std::string set = "cohen8";
  bool json = false;
  std::string sheet;  // PNG (or any OIIO format) of the set's tiles
  int tile_pixels = 48;
  std::uint64_t seed = 1;  // for filling tiles with content (see below)
};

void print_summary(const TileSet& set) {
  fmt::print("name:    {}\n", set.name);
  fmt::print("kind:    {}{}\n", set.kind == TileKind::edge ? "edge" : "corner",
             set.kind == TileKind::edge && set.has_corners ? " (corners coded too)" : "");
  fmt::print("tiles:   {}\n", set.size());
  if (set.has_edges) fmt::print("colors:  {} N/S, {} E/W\n", set.horizontal_colors, set.vertical_colors);
  if (set.has_corners) fmt::print("corners: {} colors\n", set.corner_colors);
}

void run(const TilesetOptions& options) {
  const TileSet set = load_tileset(options.set);
  // Tile contents (Poisson points per tile, --per-tile N --relax R --out tiles.json) plug in
  // here: fill the set, then write it with write_tileset_json's format plus per-tile keys
  // (points, radius_packing, radius_tight, seed; see exporters/tileset_json.h).
  if (!options.sheet.empty()) write_image(options.sheet, draw_tileset_sheet(set, options.tile_pixels));
  if (options.json) {
    fmt::print("{}", format_tileset_json(tileset_to_json(set)));
  } else if (options.sheet.empty()) {
    print_summary(set);
  }
}

}  // namespace

void register_tileset_command(CLI::App& app, const GlobalOptions&) {
  auto* sub = app.add_subcommand("tileset", "Print, draw or fill a Wang tile set");
  auto options = std::make_shared<TilesetOptions>();
  sub->add_option("--set", options->set,
                  "Built-in set (cohen8, cohen12, cohen18, owen12, complete-edge-K, corner-K, cohen8-corners, "
                  "cohen8-corners-full) or a JSON file (docs/tileset-format.md)")
      ->capture_default_str();
  sub->add_flag("--json", options->json, "Print the set as JSON");
  sub->add_option("--sheet", options->sheet, "Draw the set's tiles with their edge/corner colors into this PNG");
  sub->add_option("--tile-pixels", options->tile_pixels, "Size of each tile on the sheet, in pixels")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  sub->callback([options] { run(*options); });
}

}  // namespace wangscape::cli
