// wangscape ldi build SCENE.toml --out PACK: every tile of the scene's set sampled into
// pre-shaded LDIs (renders/ldi/ldi_build.h); ldi info PACK [--json]; ldi sheet PACK --tile K --out PNG.
#include <fmt/core.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/command.h"
#include "cli/progress.h"
#include "folder/ldi_info.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/ldi/ldi_sheet.h"

namespace wangscape::cli {

LdiSceneObserver ldi_terminal_observer(const GlobalOptions& global, std::unique_ptr<Progress>& progress) {
  LdiSceneObserver observer;
  if (!chatty(global)) return observer;
  const auto start = std::chrono::steady_clock::now();
  observer.stage = [](const std::string& message) { std::fprintf(stderr, "wangscape: %s\n", message.c_str()); };
  observer.progress = [&progress, &global, start](std::uint64_t done, std::uint64_t total, std::uint64_t rays) {
    if (!progress) progress = std::make_unique<Progress>("LDIs", total, global.quiet);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress->update(done, fmt::format("{} / {} LDIs, {:.1f} M rays/s", done, total, double(rays) / 1e6 / seconds));
  };
  return observer;
}

namespace {

// The view flags override the scene file's [ldi] section.
struct LdiBuildArgs {
  std::string scene, out;
  std::optional<double> head_height;
  std::optional<int> levels, directions, sky_rays;
  LdiGround ground = LdiGround::visible;
};

void run_ldi_build(const LdiBuildArgs& args, const GlobalOptions& global) {
  const WriteReport said(global.quiet);
  const SceneConfig config = load_scene_config(args.scene);
  LdiBuildOptions options = ldi_options(config);
  options.view.head_height = args.head_height.value_or(options.view.head_height);
  options.view.levels = args.levels.value_or(options.view.levels);
  options.view.directions = args.directions.value_or(options.view.directions);
  options.shading.ao_rays = args.sky_rays.value_or(options.shading.ao_rays);
  options.ground = args.ground;
  std::unique_ptr<Progress> progress;
  const LdiSceneObserver observer = ldi_terminal_observer(global, progress);
  const LdiBuildReport report = build_scene_ldi_pack(config, args.out, options, observer);
  progress.reset();
  said.wrote(args.out,
             fmt::format("{} LDIs, {:.1f} M depth pixels, {:.1f} M rays", report.ldis,
                         double(report.depth_pixels) / 1e6, double(report.primary_rays + report.secondary_rays) / 1e6));
}

}  // namespace

void register_ldi_command(CLI::App& app, const GlobalOptions& global) {
  auto* ldi = app.add_subcommand("ldi", "Pre-shaded Layered Depth Images of a scene's tiles (docs/ldi-pack-format.md)");
  ldi->require_subcommand(1);

  auto* build = ldi->add_subcommand("build", "Sample every tile of a scene into an LDI pack with Embree");
  auto args = std::make_shared<LdiBuildArgs>();
  build->add_option("scene", args->scene, "Scene file (TOML, see docs/scene-file.md)")->required();
  build->add_option("--out,-o", args->out, "The pack to write")->required()->check(output_file_path());
  build->add_option("--head-height", args->head_height, "Viewer's eye above the ground (m; default: [ldi])")
      ->check(CLI::Range(0.1, 100.0));
  build->add_option("--levels", args->levels, "Levels of detail (1 .. 64 tiles away)")->check(CLI::Range(1, 64));
  build->add_option("--directions", args->directions, "View directions around a tile")->check(CLI::Range(1, 64));
  build->add_option("--sky-rays", args->sky_rays, "Ambient-occlusion rays per sample")->check(CLI::Range(0, 1024));
  add_enum_option(build, "--ground", args->ground, kLdiGroundNames,
                  "The ground in the LDIs: none, visible (where it shows through), always");
  set_help_footer(build, "the pack --out (docs/ldi-pack-format.md), the file `wangscape view` maps",
                  {"wangscape ldi build templates/scenes/small.toml --out small.ldi",
                   "wangscape ldi build templates/scenes/small.toml --out small-near.ldi --levels 1 --directions 4"});
  build->callback([args, &global] { run_ldi_build(*args, global); });

  auto* info = ldi->add_subcommand("info", "Print what a pack holds: sizes, resolutions, layers, bytes");
  auto info_args = std::make_shared<std::pair<std::string, bool>>();
  info->add_option("pack", info_args->first, "LDI pack")->required();
  info->add_flag("--json", info_args->second, "One JSON object instead of text");
  set_help_footer(info, "nothing: the pack's figures on stdout",
                  {"wangscape ldi build templates/scenes/small.toml --out small.ldi", "wangscape ldi info small.ldi",
                   "wangscape ldi info small.ldi --json"});
  info->callback([info_args] {
    const LdiPack pack(info_args->first);
    std::fputs((info_args->second ? ldi_info_json(pack) : ldi_info_text(pack)).c_str(), stdout);
  });

  auto* sheet = ldi->add_subcommand("sheet", "Draw one tile's LDIs: levels as rows, directions as columns");
  struct SheetArgs {
    std::string pack, out;
    std::uint32_t tile = 0;
    int cell = 160;
  };
  auto sheet_args = std::make_shared<SheetArgs>();
  sheet->add_option("pack", sheet_args->pack, "LDI pack")->required();
  sheet->add_option("--tile", sheet_args->tile, "Tile index")->required();
  sheet->add_option("--out,-o", sheet_args->out, "Image to write (PNG)")->required()->check(output_file_path());
  sheet->add_option("--cell", sheet_args->cell, "Pixels per LDI in the sheet")
      ->capture_default_str()
      ->check(CLI::Range(8, 2048));
  set_help_footer(sheet, "the PNG --out: the front layer shaded (left) and the layer count (right) of each LDI",
                  {"wangscape ldi build templates/scenes/small.toml --out small.ldi",
                   "wangscape ldi sheet small.ldi --tile 0 --out sheet.png"});
  set_help_footer(ldi, "see each command's --help",
                  {"wangscape ldi build templates/scenes/small.toml --out small.ldi",
                   "wangscape ldi info small.ldi --json", "wangscape ldi sheet small.ldi --tile 0 --out sheet.png"});
  sheet->callback([sheet_args, &global] {
    const WriteReport report(global.quiet);
    write_ldi_sheet(sheet_args->pack, sheet_args->tile, sheet_args->out, sheet_args->cell);
    report.wrote(sheet_args->out, fmt::format("tile {}", sheet_args->tile));
  });
}

}  // namespace wangscape::cli
