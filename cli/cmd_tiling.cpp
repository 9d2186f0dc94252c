// wangscape tiling --set NAME|FILE --size WxH --seed S [--algorithm scanline|bottom-left|hash|aperiodic]
//   [--origin I,J] [--no-identical-neighbours] [--out FILE.png|FILE.csv] [--stats] [--json]
#include <fmt/core.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/progress.h"
#include "core/json_text.h"
#include "core/number_text.h"
#include "exporters/image_io.h"
#include "exporters/reports.h"
#include "generator/tiling_preview.h"
#include "generator/tiling_stats.h"
#include "scene/tileset_file.h"

namespace wangscape::cli {

namespace {

struct TilingCommandOptions {
  std::string set = "cohen8";
  std::string size = "64x64";
  std::uint64_t seed = 1;
  std::string algorithm = "scanline";
  std::string origin = "0,0";
  bool no_identical_neighbours = false;
  std::string out;
  int pixels_per_tile = 4;
  bool stats = false;
  bool json = false;
};

constexpr int kMaxSide = 1'000'000;

std::string validate_size(const std::string& text) {
  int w = 0, h = 0;
  if (!parse_number_pair(text, 'x', w, h)) return "size '" + text + "' is not WxH (e.g. 64x48)";
  if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide)
    return "size '" + text + "': width and height must be 1.." + std::to_string(kMaxSide) + " tiles";
  return "";
}

std::string validate_origin(const std::string& text) {
  std::int64_t i = 0, j = 0;
  return parse_number_pair(text, ',', i, j) ? "" : "origin '" + text + "' is not I,J (two integers, e.g. -10,5)";
}

void run(const TilingCommandOptions& options, const GlobalOptions& global) {
  const WriteReport report(global.quiet);
  const std::filesystem::path out(options.out);
  const std::string extension = out.extension().string();
  if (!options.out.empty() && extension != ".png" && extension != ".csv")
    throw std::runtime_error("output '" + options.out + "': expected a .png (tile map) or .csv (i,j,tile) file");
  const TileSet set = load_tileset(options.set);
  TilingOptions tiling_options;
  tiling_options.algorithm = parse_tiling_algorithm(options.algorithm);
  tiling_options.seed = options.seed;
  tiling_options.forbid_identical_neighbours = options.no_identical_neighbours;
  int width = 0, height = 0;
  parse_number_pair(options.size, 'x', width, height);
  parse_number_pair(options.origin, ',', tiling_options.origin_i, tiling_options.origin_j);
  Progress progress("tiling", static_cast<std::uint64_t>(height), global.quiet);
  const Tiling tiling =
      make_tiling(set, width, height, tiling_options, [&](int rows) { progress.update(std::uint64_t(rows)); });
  progress.finish();
  if (extension == ".png") write_image(out, draw_tile_map(tiling, options.pixels_per_tile));
  if (extension == ".csv") write_tiling_csv(out, tiling);
  if (options.stats || options.json) {
    const TilingStats stats = compute_tiling_stats(set, tiling);
    const TilingRun run{options.algorithm, options.seed, options.no_identical_neighbours};
    if (options.json)
      fmt::print("{}\n", json_text(tiling_stats_json(set, tiling, run, stats), 2));
    else
      fmt::print("{}", tiling_stats_text(set, tiling, run, stats));
  }
  if (!options.out.empty()) report.wrote(options.out, fmt::format("{} x {} tiles", width, height));
}

}  // namespace

void register_tiling_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("tiling", "Tile a window of the plane with a tile set");
  auto options = std::make_shared<TilingCommandOptions>();
  sub->add_option("--set", options->set, "Built-in tile set or a JSON file (see `wangscape tileset --help`)")
      ->capture_default_str();
  sub->add_option("--size", options->size, "Window size in tiles, WxH")
      ->check(CLI::Validator(validate_size, "WxH", "size"))
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "Random seed")->check(seed_number())->capture_default_str();
  sub->add_option("--algorithm", options->algorithm,
                  "scanline (north-west to south-east), bottom-left (south-west start), hash (O(1) random access, "
                  "complete sets) or aperiodic (Culik's strictly aperiodic culik13 only)")
      ->check(CLI::IsMember(tiling_algorithm_names()))
      ->capture_default_str();
  sub->add_option("--origin", options->origin, "Tile coordinates I,J of the window's south-west tile (i east, j north)")
      ->check(CLI::Validator(validate_origin, "I,J", "origin"))
      ->capture_default_str();
  sub->add_flag("--no-identical-neighbours", options->no_identical_neighbours,
                "Never lay a tile next to an identical copy of itself (fails if the set cannot avoid it)");
  sub->add_option("--out", options->out, "Output: .png pseudo-colored tile map (north up) or .csv with i,j,tile")
      ->check(output_file_path());
  sub->add_option("--pixels-per-tile", options->pixels_per_tile, "Tile map block size in pixels")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  sub->add_flag("--stats", options->stats, "Print validity, tile frequencies, identical-neighbour rate, periodicity");
  sub->add_flag("--json", options->json, "Print the statistics as JSON");
  set_help_footer(
      sub, "--out FILE: a PNG tile map (north up) or a CSV of i,j,tile; --stats: statistics on stdout",
      {"wangscape tiling --set cohen8 --size 64x64 --seed 3 --out map.png --stats",
       "wangscape tiling --set complete-edge-2 --algorithm hash --origin -1000,250 --size 32x32 --out "
       "window.csv",
       "wangscape tiling --set culik13 --algorithm aperiodic --size 256x256 --seed 2 --out culik.png --json"});
  sub->callback([options, &global] { run(*options, global); });
}

}  // namespace wangscape::cli
