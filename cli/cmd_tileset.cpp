// wangscape tileset --set NAME|FILE [--json] [--sheet sheet.png]: print or draw a tile set.
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "cli/command.h"
#include "cli/progress.h"
#include "core/number_text.h"
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
  std::uint64_t seed = 1;             // for filling tiles with content (see below)
  int per_tile = 0;                   // Poisson points per tile; 0 = colors only
  int relax = 0;                      // relaxation rounds after dart throwing
  std::string out;                    // the filled set as JSON (docs/filled-tileset-format.md)
  std::vector<PoissonClass> classes;  // --class, repeated: several classes in one fill
  bool quiet = false;                 // --quiet: no stage message
  std::optional<WriteReport> report;
};

// The line of what was written (--out, --sheet), unless --quiet.
void say_written(const TilesetOptions& options, const std::string& details) {
  std::vector<std::filesystem::path> written;
  if (!options.out.empty()) written.push_back(options.out);
  if (!options.sheet.empty()) written.push_back(options.sheet);
  if (!written.empty()) options.report->wrote(written, details);
}

// --class SHARE[:PACKING[:TIGHT]][:edge]: a class of a multi-class fill (radii in tile sides).
PoissonClass parse_class(const std::string& text) {
  std::string numbers = text;
  PoissonClass c;
  if (const std::string edge = ":edge"; numbers.size() > edge.size() && numbers.ends_with(edge)) {
    c.edge_objects = true;
    numbers.resize(numbers.size() - edge.size());
  }
  const auto values = parse_number_list(numbers, ':', 1, 3);
  if (!values || (*values)[0] <= 0 || (values->size() > 1 && (*values)[1] < 0) ||
      (values->size() > 2 && (*values)[2] < 0))
    throw std::runtime_error("tileset: --class '" + text +
                             "'; expected SHARE[:PACKING[:TIGHT]][:edge], share > 0, radii >= 0 in tile sides "
                             "(e.g. 0.7, 0.25:0.03, 0.05:0.08:0.06:edge)");
  c.share = (*values)[0];
  if (values->size() > 1) c.packing_radius = (*values)[1];
  if (values->size() > 2) c.tight_radius = (*values)[2];
  return c;
}

// Per class: points per tile against the target, radii, and the least distance to every class
// over every configuration of the set.
std::string class_fill_text(const FilledTileSet& filled, const PoissonFillOptions& options,
                            const PoissonFillReport& report) {
  const std::size_t n = filled.classes.size();
  std::vector<std::size_t> count(n, 0);
  for (const auto& tile : filled.tiles)
    for (const TilePoint& p : tile) ++count[p.species];
  double total_share = 0;
  for (const PoissonClass& c : options.classes) total_share += c.share;
  const std::vector<double>& least = report.class_min_distance;
  const std::size_t stride = std::size_t(std::lround(std::sqrt(double(least.size()))));  // classes with points
  std::string text = "class  per tile (target)  packing   tight  spacing  least distance to class 0, 1, ..\n";
  for (std::size_t c = 0; c < n; ++c) {
    text += fmt::format("{:5}  {:>8} ({:>6})  {:>7}  {:>6}  {:>7} ", c,
                        fixed_text(double(count[c]) / double(filled.tiles.size()), 2),
                        fixed_text(options.points_per_tile * options.classes[c].share / total_share, 2),
                        fixed_text(filled.classes[c].packing, 4), fixed_text(filled.classes[c].tight, 4),
                        fixed_text(filled.classes[c].spacing, 4));
    for (std::size_t k = 0; k < n; ++k)
      text += fmt::format(" {}", c < stride && k < stride ? fixed_text(least[c * stride + k], 4) : "-");
    text += filled.classes[c].edge_objects ? "  (edge objects)\n" : "\n";
  }
  return text;
}

// --per-tile N: fill the set with Poisson-disk points, write --out, draw --sheet with discs.
void fill(const TileSet& set, const TilesetOptions& options) {
  PoissonFillOptions fill_options;
  fill_options.points_per_tile = options.per_tile;
  fill_options.relax_rounds = options.relax;
  fill_options.seed = options.seed;
  fill_options.classes = options.classes;
  if (const auto estimate = estimate_poisson_fill(set, fill_options);
      !options.quiet && estimate.seconds > 5 && estimate.seconds <= kMaxFillSeconds)
    fmt::print(stderr, "wangscape: filling {:.0f} points, about {:.0f} s\n", estimate.points, estimate.seconds);
  PoissonFillReport report;
  const FilledTileSet filled = fill_poisson_tiles(set, fill_options, &report);
  if (!options.out.empty()) write_filled_tileset_json(options.out, filled);
  if (!options.sheet.empty())
    write_image(options.sheet, draw_filled_tileset_sheet(filled, std::max(options.tile_pixels, 96)));
  fmt::print("{}", poisson_fill_text(filled, report, options.per_tile));
  if (!options.classes.empty()) fmt::print("{}", class_fill_text(filled, fill_options, report));
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
  sub->add_option("--sheet", options->sheet, "Draw the set's tiles with their edge/corner colors into this PNG")
      ->check(output_file_path());
  sub->add_option("--tile-pixels", options->tile_pixels, "Size of each tile on the sheet, in pixels")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "Random seed")->check(seed_number())->capture_default_str();
  sub->add_option("--per-tile", options->per_tile, "Fill every tile with this many Poisson-disk points")
      ->check(CLI::Range(1, kMaxPointsPerTile));
  sub->add_option("--relax", options->relax, "Relaxation rounds after dart throwing (stops before a lattice)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  sub->add_option("--out", options->out, "With --per-tile: write the filled set as JSON")->check(output_file_path());
  sub->add_option_function<std::vector<std::string>>(
         "--class",
         [options](const std::vector<std::string>& values) {
           options->classes.clear();
           for (const std::string& v : values) options->classes.push_back(parse_class(v));
         },
         "With --per-tile: one class of several sharing the tiles, repeated: SHARE[:PACKING[:TIGHT]][:edge] "
         "(relative share of the points; radii in tile sides, 0 = from the density; edge = objects across edges)")
      ->type_name("SHARE[:PACKING[:TIGHT]][:edge]");
  set_help_footer(
      sub,
      "the set's summary on stdout (--json: the set as JSON); --sheet: a PNG; --per-tile N --out FILE: "
      "the filled set as JSON, for scatter and scene files",
      {"wangscape tileset --set cohen8 --json > cohen8.json",
       "wangscape tileset --set cohen8 --per-tile 20 --relax 20 --seed 1 --out tiles.json --sheet discs.png",
       "wangscape tileset --set cohen8 --per-tile 40 --class 0.7 --class 0.25 --class 0.05:0.08:0.06:edge --sheet "
       "meadow.png"});
  sub->callback([options, &global] {
    options->quiet = global.quiet;
    options->report.emplace(global.quiet);
    run(*options);
  });
}

}  // namespace wangscape::cli
