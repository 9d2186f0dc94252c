// wangscape noise tiles / texture tiles: Wang tiles as PNG + JSON (docs/texture-tiles.md), with
// an optional preview tiling. The work is in exporters/texture_tile_files.h.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "cli/command.h"
#include "cli/progress.h"
#include "exporters/texture_tile_files.h"

namespace wangscape::cli {

template <class Job>  // --set, --out, --preview WxH FILE: the same in both commands
static CLI::App* add_tiles(CLI::App& app, const GlobalOptions& global, const char* name, const char* help,
                           std::shared_ptr<Job> job) {
  auto* sub = app.add_subcommand(name, help)->require_subcommand(1)->add_subcommand("tiles", help);
  sub->add_option("--set", job->set, "Built-in tile set or tile-set JSON")->capture_default_str();
  sub->add_option("--out", job->out, "Folder for the tile PNGs and JSON")->required()->check(non_empty_path());
  const auto preview = [job](const std::vector<std::string>& v) {
    std::string file = v[1];
    if (const std::string fault = output_file_path()(file); !fault.empty())
      throw CLI::ValidationError("--preview", fault);
    job->preview_size = v[0], job->preview = v[1];
  };
  sub->add_option_function<std::vector<std::string>>("--preview", preview,
                                                     "Also write a WxH-pixel image FILE of the tiles laid in a tiling")
      ->type_size(2)  // one value of two words: the help shows "WxH FILE", not "TEXT x 2"
      ->expected(1)
      ->type_name("WxH FILE");
  sub->callback([job, &global] {
    const WriteReport report(global.quiet);
    fmt::print("{}\n", run_tiles_job(*job));
    std::vector<std::filesystem::path> written{job->out};
    if (!job->preview.empty()) written.push_back(job->preview);
    report.wrote(written, {});
  });

  return sub;
}

void register_tiles_commands(CLI::App& app, const GlobalOptions& global) {
  auto noise = std::make_shared<NoiseTilesJob>();
  auto* n = add_tiles(app, global, "noise", "Perlin-noise Wang tiles: noise that joins without seams across tile edges",
                      noise);
  n->add_option("--lattice", noise->options.lattice, "Cells per tile side (power of two)")->capture_default_str();
  n->add_option("--octaves", noise->options.octaves, "Mip levels (0 = all)")->check(CLI::Range(0, 12));
  n->add_option_function<std::string>(
       "--pattern", [noise](const std::string& name) { noise->pattern = parse_noise_pattern(name.c_str()); },
       "noise, fbm, turbulence, marble or wood: the preview's (default turbulence) and the tile files' (default fbm; "
       "marble and wood are patterns of the whole tiling, shown in the preview, over tiles of fbm)")
      ->check(CLI::IsMember({"noise", "fbm", "turbulence", "marble", "wood"}))
      ->type_name("PATTERN");
  // `noise --help` and `noise tiles --help` (texture likewise) end alike.
  const auto writes = [](const char* kind) {
    return std::string("the folder --out: one PNG per tile and ") + kind +
           "_tiles.json (docs/texture-tiles.md); --preview: an image of the tiles laid in a tiling";
  };
  for (CLI::App* a : {n, n->get_parent()})
    set_help_footer(a, writes("noise"),
                    {"wangscape noise tiles --set corner-3 --lattice 32 --octaves 3 --out noise --preview 1024x512 "
                     "noise.png",
                     "wangscape noise tiles --set corner-3 --pattern marble --out marble --preview 512x256 marble.png",
                     "wangscape noise tiles --set cohen8 --out noise8"});
  auto texture = std::make_shared<TextureTilesJob>();
  auto* t = add_tiles(app, global, "texture",
                      "Texture Wang tiles quilted from an exemplar image, seamless across tile edges", texture);
  const auto slot = [texture](std::size_t k) {  // whatever order CLI11 runs the two options in
    return [texture, k](const std::string& file) {
      texture->exemplars.resize(std::max<std::size_t>(texture->exemplars.size(), k + 1)), texture->exemplars[k] = file;
    };
  };
  t->add_option_function<std::string>("--exemplar", slot(0), "Exemplar image, or meadow / pumice")->required();
  t->add_option_function<std::string>("--exemplar2", slot(1), "Second exemplar (corner-marked sets)");
  t->add_option("--size", texture->options.tile_size, "Pixels per tile side")->capture_default_str();
  for (CLI::App* a : {t, t->get_parent()})
    set_help_footer(a, writes("texture"),
                    {"wangscape texture tiles --exemplar meadow --exemplar2 pumice --set corner-2 --size 64 --out tex "
                     "--preview 1024x512 tex.png",
                     "wangscape texture tiles --exemplar pumice --set cohen8 --size 64 --out pumice"});
}

}  // namespace wangscape::cli
