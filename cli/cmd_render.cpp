// wangscape render DIR --engine povray|blender|embree [--width W --height H]: renders a built
// scene folder with the real renderer (POV-Ray: DIR/render.png; Blender: DIR/render_blender.png
// and DIR/scene.blend), keeping its log beside the image; or with the Embree reference renderer
// (DIR/render_embree.png, or --out, with --spp samples per pixel). --camera/--look-at: from
// another camera, without building the folder again. --path FILE --frames FOLDER: every frame of
// a path file, as the view plays it (renders/render_path.h), and FOLDER/path.mp4.
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/scene_commands.h"
#include "core/number_text.h"
#include "core/vecmath.h"
#include "renders/render_folder.h"
#include "renders/render_path.h"
#include "renders/trace/embree_reference.h"

namespace wangscape::cli {

std::optional<std::array<double, 3>> parse_enu_triple(const std::string& text, bool third_optional) {
  const auto v = parse_number_list(text, ',', third_optional ? 2 : 3, 3);
  if (!v) return std::nullopt;
  return std::array<double, 3>{(*v)[0], (*v)[1], v->size() == 3 ? (*v)[2] : std::numeric_limits<double>::quiet_NaN()};
}

namespace {

// --path: the frames, a bar of frames on a terminal, the one line of what was written.
void run_render_path(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global) {
  const WriteReport report(global.quiet);
  if (request.camera || request.look_at)
    throw CLI::ValidationError("--camera", "a path gives every frame's camera: give --path or --camera, not both");
  if (request.fov || request.sun)
    throw CLI::ValidationError(request.fov ? "--fov" : "--sun",
                               "is for one still; a path renders the scene's lens and sun");
  if (!request.out.empty()) throw CLI::ValidationError("--out", "with --path the frames go to --frames FOLDER");
  PathRenderRequest path;
  path.engine = parse_render_engine(request.engine);
  path.path = request.path;
  path.frames = request.frames;
  path.fps = request.fps.value_or(kDefaultPathRenderFps);
  path.width = request.width;
  path.height = request.height;
  path.samples = request.spp;
  path.first_frame = request.first_frame;
  path.frame_count = request.frame_count;
  const bool part = request.first_frame > 0 || request.frame_count > 0;
  std::optional<Progress> progress;
  long long skipped = 0;
  const auto start = std::chrono::steady_clock::now();
  if (chatty(global))
    std::fprintf(stderr, "wangscape: rendering %s along %s with %s\n", dir.string().c_str(),
                 shown_path(request.path).c_str(), request.engine.c_str());
  path.on_frame = [&](long long done, long long total, bool rendered) {
    if (!rendered) ++skipped;
    if (!progress) progress.emplace("frames", std::uint64_t(total), global.quiet, false);
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const long long fresh = done - skipped;
    progress->update(std::uint64_t(done), fresh > 0 ? fmt::format("frame {} / {}, about {:.0f} s left", done, total,
                                                                  spent / double(fresh) * double(total - done))
                                                    : fmt::format("frame {} / {}, done before", done, total));
  };
  const PathRenderResult result = render_path(dir, path);
  progress.reset();
  std::string details = fmt::format("{} frames of {}x{} at {} frames/s with {}", result.frames, result.width,
                                    result.height, number_text(path.fps), request.engine);
  if (result.skipped > 0) details += fmt::format(", {} there already", result.skipped);
  if (part)
    details += fmt::format(" (frames {} .. {}; path.mp4 only for the whole path)", request.first_frame,
                           request.first_frame + result.frames - 1);
  else
    details += result.movie.empty() ? "; no ffmpeg on PATH: PNG frames only" : " and path.mp4";
  if (!result.blend.empty()) details += ", path.blend";
  if (!result.log.empty()) details += "; log " + shown_path(result.log);
  report.wrote(request.frames, details);
}

}  // namespace

void run_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global) {
  if (!request.path.empty() || !request.frames.empty() || request.fps || request.first_frame > 0 ||
      request.frame_count > 0) {
    if (request.path.empty())
      throw CLI::ValidationError("--path", "--frames, --fps, --first-frame and --frame-count go with --path FILE");
    if (request.frames.empty()) throw CLI::ValidationError("--frames", "--path needs --frames FOLDER for its frames");
    return run_render_path(dir, request, global);
  }
  const WriteReport report(global.quiet);
  FolderRenderRequest folder;
  folder.engine = parse_render_engine(request.engine);
  folder.width = request.width;
  folder.height = request.height;
  folder.out = request.out;
  folder.samples_per_pixel = request.spp;
  folder.eye = request.camera;
  folder.look_at = request.look_at;
  folder.fov_degrees = request.fov;
  folder.sun_degrees = request.sun;
  std::unique_ptr<Progress> progress;
  if (chatty(global)) {
    std::fprintf(stderr, "wangscape: rendering %s with %s\n", dir.string().c_str(), request.engine.c_str());
    folder.on_progress = [&](std::uint64_t done, std::uint64_t total) {
      if (total == 0) return;
      if (!progress) progress = std::make_unique<Progress>("pixels", total, global.quiet);
      progress->update(done);
    };
  }
  const auto result = render_scene_folder(dir, folder);
  progress.reset();
  std::vector<std::filesystem::path> written{result.image};
  if (!result.blend.empty()) written.push_back(result.blend);
  report.wrote(written,
               request.engine + (result.log.empty() ? "; " + result.summary : "; log " + shown_path(result.log)));
}

void register_render_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("render", "Render a scene folder written by `wangscape build` into DIR/render.png");
  auto request = std::make_shared<RenderRequest>();
  auto dir = std::make_shared<std::string>();
  auto camera = std::make_shared<std::string>(), look_at = std::make_shared<std::string>();
  auto sun = std::make_shared<std::string>();
  sub->add_option("dir", *dir, "Scene folder")->required();
  sub->add_option("--engine", request->engine, "Renderer: povray, blender or embree")->capture_default_str();
  sub->add_option("--width", request->width, "Image width in pixels (default: the scene's; alone, the height follows)")
      ->check(CLI::Range(1, 32768));
  sub->add_option("--height", request->height,
                  "Image height in pixels (default: the scene's; alone, the width follows)")
      ->check(CLI::Range(1, 32768));
  sub->add_option("--out", request->out,
                  "The image to write (default: DIR/render_embree.png; povray and blender: a copy of the folder's)")
      ->check(output_file_path());
  sub->add_option("--spp", request->spp,
                  "embree: samples per pixel (default: the scene's antialias squared); blender with --path: Cycles "
                  "samples (default: the scene's)")
      ->check(CLI::Range(1, kMaxReferenceSamples));
  sub->add_option("--camera", *camera,
                  "Render from another eye, E,N[,H] (ENU m; without H: the [ldi] head height above the ground)");
  sub->add_option("--look-at", *look_at, "With or without --camera: the point looked at, E,N,H (ENU m)");
  sub->add_option("--fov", request->fov,
                  "embree and povray: the horizontal field of view in degrees (default: the scene's)")
      ->check(CLI::Range(1e-3, kMaxFieldOfViewDegrees));
  sub->add_option("--sun", *sun,
                  "embree and povray: another sun, AZIMUTH,ELEVATION in degrees as [sun] gives them (azimuth "
                  "clockwise from north, -360 .. 360; elevation -90 .. 90)");
  sub->add_option("--path", request->path,
                  "Render every frame along a path file (the view's: docs/viewer.md) into --frames");
  sub->add_option("--frames", request->frames,
                  "With --path: the folder of frames, frame-00000.png ... and path.mp4 (ffmpeg); frames already "
                  "there and complete are kept, not rendered again");
  sub->add_option("--fps", request->fps, "With --path: frames per second along the path (1 .. 240, default 24)")
      ->check(finite_number());
  sub->add_option("--first-frame", request->first_frame,
                  "With --path: render from this frame (default 0), e.g. one part of a path per machine")
      ->check(CLI::Range(0LL, 100000000LL));
  sub->add_option("--frame-count", request->frame_count,
                  "With --path: render this many frames (default: to the path's end); path.mp4 only for the whole path")
      ->check(CLI::Range(1LL, 100000000LL));
  set_help_footer(sub,
                  "into the folder: render.png and povray.log (povray); scene.blend, render_blender.png and "
                  "blender.log (blender), with --out a copy there; render_embree.png or --out (embree). With --path: "
                  "FRAMES/frame-NNNNN.png and FRAMES/path.mp4 (blender: also FRAMES/path.blend, its camera "
                  "keyframed)",
                  {"wangscape build templates/scenes/small.toml --out small",
                   "wangscape render small --engine embree --spp 4 --camera 0,6570 --look-at 0,6540,1117.2 --out "
                   "small/close.png",
                   "wangscape render small --engine embree --path templates/paths/small_walk.json --frames small/walk "
                   "--fps 4 --width 160"});
  sub->callback([dir, request, camera, look_at, sun, &global] {
    if (!sun->empty()) {
      const auto angles = parse_number_list(*sun, ',', 2, 2);
      if (!angles || !(std::abs((*angles)[0]) <= 360) || !(std::abs((*angles)[1]) <= 90))
        throw CLI::ValidationError("--sun",
                                   "'" + *sun + "' is not AZIMUTH,ELEVATION in degrees (-360 .. 360, -90 .. 90)");
      request->sun = std::array<double, 2>{(*angles)[0], (*angles)[1]};
    }
    if (!camera->empty() && !(request->camera = parse_enu_triple(*camera, true)))
      throw CLI::ValidationError("--camera", "'" + *camera + "' is not E,N or E,N,H in meters");
    if (!look_at->empty() && !(request->look_at = parse_enu_triple(*look_at, false)))
      throw CLI::ValidationError("--look-at", "'" + *look_at + "' is not E,N,H in meters");
    run_render(*dir, *request, global);
  });
}

}  // namespace wangscape::cli
