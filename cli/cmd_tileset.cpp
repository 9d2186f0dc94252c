// wangscape tileset --set NAME|FILE [--json] [--sheet sheet.png]: print or draw a tile set.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "cli/command.h"
#include "cli/progress.h"
#include "exporters/image_io.h"
#include "exporters/reports.h"
#include "generator/tiling_preview.h"
#include "scene/filled_tileset_file.h"
#include "scene/tileset_file.h"

namespace wangscape::cli {

namespace {

struct TilesetOptions {
  std::string set = "cohen8";
  bool json = false;
  std::string sheet;  // PNG (or any OIIO format) of the set's tiles
  int tile_pixels = 48;
  std::uint64_t seed = 1;  // for filling tiles with content (see below)
  int per_tile = 0;        // Poisson points per tile; 0 = colors only
  int relax = 0;           // relaxation rounds after dart throwing
  std::string out;         // the filled set as JSON (docs/filled-tileset-format.md)
  bool quiet = false;      // --quiet: no stage message
  std::optional<WriteReport> report;
};

// The line of what was written (--out, --sheet), unless --quiet.
void say_written(const TilesetOptions& options, const std::string& details) {
  std::vector<std::filesystem::path> written;
  if (!options.out.empty()) written.push_back(options.out);
  if (!options.sheet.empty()) written.push_back(options.sheet);
  if (!written.empty()) options.report->wrote(written, details);
}

// --per-tile N: fill the set with Poisson-disk points, write --out, draw --sheet with discs.
void fill(const TileSet& set, const TilesetOptions& options) {
  PoissonFillOptions fill_options;
  fill_options.points_per_tile = options.per_tile;
  fill_options.relax_rounds = options.relax;
  fill_options.seed = options.seed;
  if (const auto estimate = estimate_poisson_fill(set, fill_options);
      !options.quiet && estimate.seconds > 5 && estimate.seconds <= kMaxFillSeconds)
    fmt::print(stderr, "wangscape: filling {:.0f} points, about {:.0f} s\n", estimate.points, estimate.seconds);
  PoissonFillReport report;
  const FilledTileSet filled = fill_poisson_tiles(set, fill_options, &report);
  if (!options.out.empty()) write_filled_tileset_json(options.out, filled);
  if (!options.sheet.empty())
    write_image(options.sheet, draw_filled_tileset_sheet(filled, std::max(options.tile_pixels, 96)));
  fmt::print("{}", poisson_fill_text(filled, report, options.per_tile));
  std::size_t points = 0;
  for (const auto& tile : filled.tiles) points += tile.size();
  say_written(options, fmt::format("{} tiles filled with {} points", filled.tiles.size(), points));
}

void run(const TilesetOptions& options) {
  const TileSet set = load_tileset(options.set);
  if (options.per_tile > 0) return fill(set, options);
  if (!options.out.empty()) throw std::runtime_error("--out needs --per-tile N (the points to write)");
  if (!options.sheet.empty()) write_image(options.sheet, draw_tileset_sheet(set, options.tile_pixels));
  say_written(options, fmt::format("{} tiles", set.tiles.size()));
  if (options.json) {
    fmt::print("{}", format_tileset_json(tileset_to_json(set)));
  } else if (options.sheet.empty()) {
    fmt::print("{}", tileset_summary_text(set));
  }
}

}  // namespace

void register_tileset_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("tileset", "Print, draw or fill a Wang tile set");
  auto options = std::make_shared<TilesetOptions>();
  sub->add_option("--set", options->set,
                  "Built-in set (cohen8, cohen12, cohen18, owen12, complete-edge-K, corner-K, cohen8-corners, "
                  "cohen8-corners-full, culik13: aperiodic) or a JSON file (docs/tileset-format.md)")
      ->capture_default_str();
  sub->add_flag("--json", options->json, "Print the set as JSON");
  sub->add_option("--sheet", options->sheet, "Draw the set's tiles with their edge/corner colors into this PNG");
  sub->add_option("--tile-pixels", options->tile_pixels, "Size of each tile on the sheet, in pixels")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "Random seed")->check(seed_number())->capture_default_str();
  sub->add_option("--per-tile", options->per_tile, "Fill every tile with this many Poisson-disk points")
      ->check(CLI::Range(1, kMaxPointsPerTile));
  sub->add_option("--relax", options->relax, "Relaxation rounds after dart throwing (stops before a lattice)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  sub->add_option("--out", options->out, "With --per-tile: write the filled set as JSON");
  set_help_footer(
      sub,
      "the set's summary on stdout (--json: the set as JSON); --sheet: a PNG; --per-tile N --out FILE: "
      "the filled set as JSON, for scatter and scene files",
      {"wangscape tileset --set cohen8 --json > cohen8.json", "wangscape tileset --set cohen8 --sheet sheet.png",
       "wangscape tileset --set cohen8 --per-tile 20 --relax 20 --seed 1 --out tiles.json --sheet discs.png"});
  sub->callback([options, &global] {
    options->quiet = global.quiet;
    options->report.emplace(global.quiet);
    run(*options);
  });
}

}  // namespace wangscape::cli
