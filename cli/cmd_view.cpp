// wangscape view DIR: the real-time LDI view of a scene folder built with [exports] ldi — a
// window, or offline frames, frame statistics and path playback (docs/viewer.md).
#include <limits>
#include <memory>

#include "cli/command.h"
#include "core/number_text.h"
#include "renders/window/view_program.h"

namespace wangscape::cli {

namespace {
// "A,B" or "A,B,C" as numbers (a missing third is NaN); empty when it is not that.
std::optional<std::array<double, 3>> parse_triple(const std::string& text, bool third_optional) {
  const auto v = parse_number_list(text, ',', third_optional ? 2 : 3, 3);
  if (!v) return std::nullopt;
  return std::array<double, 3>{(*v)[0], (*v)[1], v->size() == 3 ? (*v)[2] : std::numeric_limits<double>::quiet_NaN()};
}
}  // namespace

void register_view_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("view", "Walk through a scene folder's field in a window, or render its LDI frames");
  struct Options {
    ViewRequest request;
    std::string dir, camera, look_at, size, engine = "auto";
  };
  auto o = std::make_shared<Options>();
  sub->add_option("dir", o->dir, "Scene folder written by `wangscape build` with [exports] ldi")->required();
  sub->add_option("--camera", o->camera, "Eye E,N[,H] (ENU m; without H: head height above the ground)");
  sub->add_option("--look-at", o->look_at, "Point looked at, E,N,H (ENU m)");
  sub->add_option("--fov", o->request.fov_degrees, "Horizontal field of view, degrees")->check(finite_number());
  sub->add_option("--size", o->size, "Frame size WIDTHxHEIGHT (default: the scene's image size)");
  sub->add_option("--out", o->request.out, "Write one offline frame (PNG) instead of opening a window")
      ->check(output_file_path());
  sub->add_flag("--stats", o->request.stats, "Print frame statistics (median over --repeat frames)");
  sub->add_flag("--json", o->request.json, "With --stats: as one JSON object");
  sub->add_option("--repeat", o->request.repeat, "Frames timed for --stats (default 200)");
  sub->add_option("--path", o->request.path, "Keyframes JSON to fly along (docs/viewer.md)");
  sub->add_option("--frames", o->request.frames_dir, "Folder for the path's frames (and path.mp4 with ffmpeg)");
  sub->add_option("--fps", o->request.fps,
                  "Frames per second: of the path (default 24), or the rate the window holds (default 60); each "
                  "frame traces anew what a frame at that rate has time for, the rest reused from the frame before "
                  "(1 .. 240)")
      ->check(finite_number());
  sub->add_option("--compare-every", o->request.compare_every,
                  "With --path: compare frames 0, K, 2K, ... with the truth and the exact one-sample image (one JSON "
                  "line each)");
  sub->add_flag(
      "--no-cache", [o](std::int64_t) { o->request.cached = false; },
      "With --path: draw every frame whole instead of from the frame before");
  sub->add_option("--record", o->request.record,
                  "Window: where the keyframes dropped with K go on exit, a path file for --path (default path.json)")
      ->check(output_file_path());
  sub->add_option("--script", o->request.script, "Window: scripted input, e.g. \"W*30,screenshot,Escape\"");
  sub->add_flag("--compare", o->request.compare,
                "Also ray trace the frame with Embree (the truth, and the exact geometry at one sample per pixel) "
                "and print PSNR, SSIM and holes of both against the truth");
  sub->add_option("--diff", o->request.diff, "With --compare: write the frame's difference from the truth (PNG)")
      ->check(output_file_path());
  sub->add_option("--truth-spp", o->request.truth_samples,
                  "With --compare: the truth's samples per pixel (default 64: converged for one-sample frames)");
  sub->add_option("--reference,--truth", o->request.truth_out,
                  "With --compare: write the reference it compared against, the truth (PNG)")
      ->check(output_file_path());
  sub->add_option("--side-by-side", o->request.side_by_side,
                  "With --compare: write the frame (left) beside the reference (right), one PNG")
      ->check(output_file_path());
  sub->add_option("--threads", o->request.threads, "Threads (default: all cores)")->check(CLI::Range(0, 1024));
  sub->add_option("--detail", o->request.settings.detail,
                  "Level-of-detail scale: 1 the pack's levels, 0.5 coarser and faster, 2 finer (0.1 .. 10)")
      ->check(finite_number());
  sub->add_option("--near", o->request.settings.near_field,
                  "Near field, meters: tiles this close are ray traced from their real flowers instead of drawn "
                  "from LDIs (default 8; 0: LDIs everywhere)")
      ->check(finite_number());
  sub->add_option("--spp", o->request.settings.samples,
                  "Samples per pixel of each frame: N jittered frames averaged (anti-aliased offline frames and "
                  "paths; with --compare the exact image at N samples is the one to match; default 1)");
  sub->add_option("--engine", o->engine,
                  "auto (default): per frame, rays where the near field already fills half the frame (in "
                  "the field), else LDIs; ldi: LDIs beyond the near field; embree: every pixel ray cast (one "
                  "primary and one sun-shadow ray, the anchor the view is measured against)")
      ->check(CLI::IsMember({"auto", "ldi", "embree"}));
  set_help_footer(sub,
                  "--out: one PNG; --path with --frames: the folder of frames (and path.mp4); --stats and "
                  "--compare: figures on stdout; the window's F12 screenshots and --record's path file in the "
                  "current folder. Positions E,N,H for --camera and paths: `wangscape terrain height DIR E,N --above "
                  "1.7`",
                  {"wangscape build templates/scenes/small.toml --out small", "wangscape view small --out frame.png",
                   "wangscape view small --camera 0,6570 --look-at 0,6540,1117.2 --size 320x180 --out close.png"});
  sub->callback([o, &global] {
    ViewRequest& r = o->request;
    r.dir = o->dir;
    r.quiet = global.quiet;
    r.settings.engine = o->engine == "embree" ? ViewEngine::embree
                        : o->engine == "ldi"  ? ViewEngine::ldi
                                              : ViewEngine::automatic;
    if (!o->camera.empty() && !(r.camera = parse_triple(o->camera, true)))
      throw CLI::ValidationError("--camera", "'" + o->camera + "' is not E,N or E,N,H in meters");
    if (!o->look_at.empty() && !(r.look_at = parse_triple(o->look_at, false)))
      throw CLI::ValidationError("--look-at", "'" + o->look_at + "' is not E,N,H in meters");
    if (!o->size.empty() && !parse_number_pair(o->size, 'x', r.width, r.height))
      throw CLI::ValidationError("--size", "'" + o->size + "' is not WIDTHxHEIGHT in pixels");
    if (!o->size.empty() && (r.width < 1 || r.height < 1))
      throw CLI::ValidationError("--size", "'" + o->size + "': each side must be at least 1 pixel");
    run_view(r);
  });
}

}  // namespace wangscape::cli
