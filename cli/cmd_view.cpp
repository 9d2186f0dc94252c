// wangscape view DIR: the real-time LDI view of a scene folder built with [exports] ldi — a
// window, or offline frames, frame statistics and path playback (docs/viewer.md). The flags
// become a ViewRequest, checked before anything is read (cli/view_request.h); the view library
// (renders/view) and the window (renders/window) draw; this file writes the frames, prints the
// figures (cli/view_report.h), the progress and the one line of what was written.
#include <fmt/core.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <system_error>
#include <vector>

#include "cli/command.h"
#include "cli/progress.h"
#include "cli/view_report.h"
#include "cli/view_request.h"
#include "core/error.h"
#include "core/number_text.h"
#include "core/run_cleanup.h"
#include "exporters/image_io.h"
#include "renders/external/movie.h"
#include "renders/window/ldi_window.h"

namespace wangscape::cli {

namespace {

namespace fs = std::filesystem;

// "A", "A and B", "A, B and C".
std::string listed(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t k = 0; k < items.size(); ++k)
    text += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
  return text;
}

// --frames: the folder of a path's frames, made when the first frame is written (a path refused
// before leaves none). Until keep(), it is removed again with what this run wrote into it if the
// playback fails: the whole folder when this run made it, else this run's files.
class FramesFolder {
 public:
  explicit FramesFolder(fs::path dir) : dir_(std::move(dir)) {}
  FramesFolder(const FramesFolder&) = delete;
  FramesFolder& operator=(const FramesFolder&) = delete;
  ~FramesFolder() {
    std::error_code ec;
    if (made_) {
      fs::remove_all(dir_, ec);
      unregister_temporary(dir_);
    }
    for (const fs::path& file : written_) fs::remove(file, ec);
  }
  bool wanted() const { return !dir_.empty(); }
  const fs::path& dir() const { return dir_; }
  void open() {
    if (open_) return;
    open_ = true;
    made_ = !fs::exists(dir_);
    if (made_) register_temporary(dir_);
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (!fs::is_directory(dir_, ec)) throw Error(dir_, "", "cannot make the frames folder");
  }
  // Writes `image` as NAME-NNNNN.png, NNNNN the frame's number.
  void write(const char* name, long long frame, const ImageRgb8& image) {
    open();
    const fs::path file = dir_ / fmt::format("{}-{:05d}.png", name, frame);
    write_image(file, image);
    written_.push_back(file);
  }
  void keep() {
    if (made_) unregister_temporary(dir_);
    made_ = false;
    written_.clear();
  }

 private:
  fs::path dir_;
  bool open_ = false, made_ = false;
  std::vector<fs::path> written_;
};

// --path: every frame along the path (play_view_path), as PNGs into --frames and path.mp4, the
// compared frames' figures and --stats on stdout, a progress bar on a terminal.
void play_path(const std::shared_ptr<const ViewWorld>& world, const ViewPath& path, const ViewRequest& request,
               const PathPlayback& playback, const WriteReport& report) {
  FramesFolder folder(request.frames_dir);
  std::optional<Progress> progress;
  std::vector<double> frame_ms;
  double fresh_share = 0;
  const auto start = std::chrono::steady_clock::now();
  play_view_path(world, path, request.path, playback, [&](const PathFrame& frame) {
    if (!progress) progress.emplace("frames", std::uint64_t(frame.count), request.quiet);
    frame_ms.push_back(frame.frame_ms);
    fresh_share += frame.fresh_share;
    if (frame.comparison) {
      print_path_comparison(frame);
      if (folder.wanted()) folder.write("truth", frame.index, frame.comparison->truth);  // beside its frame
    }
    if (folder.wanted()) folder.write("frame", frame.index, *frame.image);
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto done = frame.index + 1;
    progress->update(std::uint64_t(done), fmt::format("frame {} / {}, about {:.0f} s left", done, frame.count,
                                                      spent / double(done) * double(frame.count - done)));
  });
  progress.reset();
  const auto frames = static_cast<long long>(frame_ms.size());
  if (request.stats)
    print_path_stats(frame_ms, fresh_share / double(frames), playback.width, playback.height, playback.fps,
                     request.json);
  if (!folder.wanted()) return;
  folder.open();
  const bool movie = write_frames_movie(folder.dir(), kPathFramePattern, playback.fps, folder.dir() / "path.mp4");
  folder.keep();
  report.wrote(folder.dir(), fmt::format("{} frames of {}x{}{}", frames, playback.width, playback.height,
                                         movie ? " and path.mp4" : "; no ffmpeg on PATH: PNG frames only"));
}

// --out, --stats, --compare: one camera's frame, its statistics or its comparison with the truth.
void draw_frame(const std::shared_ptr<const ViewWorld>& world, const Camera& camera, const ViewRequest& request,
                int width, int height, const WriteReport& report) {
  LdiRenderer renderer(world, width, height);
  renderer.apply(request.settings);
  const int repeat = request.repeat ? request.repeat : 200;
  const ViewFrameStats stats = request.stats ? measure_view(renderer, camera, repeat) : renderer.render(camera);
  std::vector<fs::path> written;
  std::vector<std::string> what;
  const auto write = [&](const fs::path& file, const ImageRgb8& image, const char* name) {
    write_image(file, image);
    written.push_back(file);
    what.emplace_back(name);
  };
  if (!request.out.empty()) write(request.out, renderer.image(), "the frame");
  if (request.compare) {
    const ViewComparison v = compare_with_reference(*world, renderer, camera, request.truth_samples);
    if (!request.truth_out.empty()) write(request.truth_out, v.truth, "the reference");
    if (!request.side_by_side.empty())
      write(request.side_by_side, side_by_side(renderer.image(), v.truth), "the frame beside the reference");
    if (!request.diff.empty()) write(request.diff, v.comparison.difference, "the difference");
    print_comparison(v, renderer.samples(), stats, request.truth_out, request.json);
  } else if (request.stats) {
    print_view_stats(stats, camera, width, height, repeat, request.json);
  }
  report.wrote(written, listed(what) + fmt::format(", {}x{}", width, height));
}

// The window: its options from the request; screenshots on stdout, the recorded walk's line.
void open_window(const std::shared_ptr<const ViewWorld>& world, const Camera& camera, const ViewRequest& request,
                 const WriteReport& report) {
  ViewWindowOptions options;
  options.camera = camera;
  options.width = request.width ? request.width : kDefaultWindowWidth;
  options.height = request.height ? request.height : kDefaultWindowHeight;
  check_view_memory(request, options.width, options.height, true);
  if (!request.record.empty()) options.record = request.record;
  options.script = request.script;
  options.settings = request.settings;
  options.fps = request.fps.value_or(kDefaultViewFps);
  if (!request.quiet) options.on_screenshot = [](const fs::path& file) { std::printf("%s\n", file.string().c_str()); };
  options.on_recorded = [&](const RecordedWalk& walk) {
    if (walk.written)
      report.wrote(walk.file, fmt::format("{} keyframes over {} s; replay: wangscape view DIR --path {} --frames DIR",
                                          walk.keyframes, fixed_text(walk.seconds, 1), shown_path(walk.file)));
    else if (!request.quiet)
      std::fprintf(stderr, "wangscape: one keyframe recorded; a path needs two: nothing written\n");
  };
  run_view_window(world, options);
}

void run_view(const ViewRequest& request) {
  const WriteReport report(request.quiet);
  check_view_request(request);
  const bool window = wants_window(request);
  if (window) {  // refused before the scene is assembled
    check_view_script(request.script, "--script");
    if (!display_available())
      throw Error(
          "view: no display to open a window on (DISPLAY is not set); write frames with --out FILE, --path FILE "
          "--frames DIR or --stats, or run the window under xvfb-run");
  }
  std::optional<tbb::global_control> threads;
  if (request.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(request.threads));

  // Frames too large for memory fail before the folder loads (the scene's own size: after).
  if (request.width) check_view_memory(request, request.width, request.height, window);
  // A bad path file fails before the folder loads.
  std::optional<ViewPath> path;
  PathPlayback playback;
  if (!request.path.empty()) {
    path = read_view_path(request.path);
    playback.fps = request.fps.value_or(kDefaultPathFps);
    path_frame_count(*path, playback.fps, request.path, "--fps");
  }
  const auto world = ViewWorld::load(request.dir, [&](const std::string& message) {
    if (!request.quiet) std::fprintf(stderr, "wangscape: %s\n", message.c_str());
  });
  const Camera camera = request_camera(*world, request);
  if (window) return open_window(world, camera, request, report);
  const int width = request.width ? request.width : world->scene().render.width;
  const int height = request.height ? request.height : world->scene().render.height;
  check_view_memory(request, width, height);
  if (!path) return draw_frame(world, camera, request, width, height, report);
  playback.width = width;
  playback.height = height;
  playback.fov_degrees = camera.fov_degrees;
  playback.cached = request.cached;
  playback.compare_every = request.compare_every;
  playback.truth_samples = request.truth_samples;
  playback.settings = request.settings;
  play_path(world, *path, request, playback, report);
}

}  // namespace

void register_view_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("view", "Walk through a scene folder's field in a window, or render its LDI frames");
  struct Options {
    ViewRequest request;
    std::string dir, camera, look_at, size;
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
  sub->add_option("--diff", o->request.diff,
                  "With --compare: write the frame's difference from the truth (PNG): a heat map, holes in magenta")
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
  add_enum_option(sub, "--engine", o->request.settings.engine, kViewEngineNames,
                  "auto (default): per frame, rays where the near field already fills half the frame (in "
                  "the field), else LDIs; ldi: LDIs beyond the near field; embree: every pixel ray cast (one "
                  "primary and one sun-shadow ray, the anchor the view is measured against)");
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
    if (!o->camera.empty() && !(r.camera = parse_enu_triple(o->camera, true)))
      throw CLI::ValidationError("--camera", "'" + o->camera + "' is not E,N or E,N,H in meters");
    if (!o->look_at.empty() && !(r.look_at = parse_enu_triple(o->look_at, false)))
      throw CLI::ValidationError("--look-at", "'" + o->look_at + "' is not E,N,H in meters");
    if (!o->size.empty() && !parse_number_pair(o->size, 'x', r.width, r.height))
      throw CLI::ValidationError("--size", "'" + o->size + "' is not WIDTHxHEIGHT in pixels");
    if (!o->size.empty() && (r.width < 1 || r.height < 1))
      throw CLI::ValidationError("--size", "'" + o->size + "': each side must be at least 1 pixel");
    run_view(r);
  });
}

}  // namespace wangscape::cli
