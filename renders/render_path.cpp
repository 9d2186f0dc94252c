#include "renders/render_path.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/number_text.h"
#include "core/run_cleanup.h"
#include "core/text_file.h"
#include "exporters/image_io.h"
#include "exporters/povray_writer.h"
#include "folder/scene_folder.h"
#include "renders/external/blender_render.h"
#include "renders/external/child_process.h"
#include "renders/external/movie.h"
#include "renders/external/povray_render.h"
#include "renders/render_folder.h"
#include "renders/trace/embree_reference.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

// The frames folder, made when missing; removed again when this run made it and leaves it empty
// (a refused or failed run before its first frame leaves nothing).
class FramesFolder {
 public:
  explicit FramesFolder(fs::path dir) : dir_(std::move(dir)) {
    std::error_code ec;
    made_ = !fs::exists(dir_, ec);
    if (made_) register_temporary(dir_);
    fs::create_directories(dir_, ec);
    if (!fs::is_directory(dir_)) {
      if (made_) unregister_temporary(dir_);
      throw Error(dir_, "", "cannot make the frames folder" + (ec ? " (" + ec.message() + ")" : std::string()));
    }
  }
  FramesFolder(const FramesFolder&) = delete;
  FramesFolder& operator=(const FramesFolder&) = delete;
  ~FramesFolder() {
    if (!made_) return;
    std::error_code ec;
    fs::remove(dir_, ec);  // only when empty
    unregister_temporary(dir_);
  }
  // Frames are in it: it stays, even if the run fails later.
  void keep() {
    if (made_) unregister_temporary(dir_);
    made_ = false;
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
  bool made_ = false;
};

// A folder for a renderer's unfinished frames inside the frames folder (".NAME.tmp-<pid>", as
// every temporary: a later run removes it when this one was killed), removed with what is left
// in it.
class WorkFolder {
 public:
  WorkFolder(const fs::path& frames, const std::string& name)
      : dir_(frames / ("." + name + ".tmp-" + std::to_string(::getpid()))) {
    register_temporary(dir_);
    std::error_code ec;
    fs::remove_all(dir_, ec);
    if (!fs::create_directory(dir_, ec))
      throw Error(frames, "", "cannot write in the frames folder" + (ec ? " (" + ec.message() + ")" : std::string()));
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  ~WorkFolder() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    unregister_temporary(dir_);
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

// Moves a renderer's finished frame into place as frame `k`.
void publish_frame(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw Error(to, "", "cannot move the rendered frame here: " + ec.message());
}

// One POV-Ray run of the frames `todo` of `cameras` into `frames`: the folder's `scene_pov` with
// their cameras indexed by frame_number, and the wind's time of each (frame k at k / fps), in a
// temporary .pov beside it (POV-Ray resolves includes from the folder). Returns the log.
fs::path render_povray_frames(const fs::path& dir, const fs::path& scene_pov, const fs::path& frames,
                              const std::vector<Camera>& cameras, const std::vector<long long>& todo, double fps,
                              int width, int height,
                              const std::function<void(long long, const fs::path&)>& frame_done) {
  std::vector<Camera> todo_cameras;
  std::vector<double> todo_seconds;
  for (const long long k : todo) {
    todo_cameras.push_back(cameras[std::size_t(k)]);
    todo_seconds.push_back(double(k) / fps);
  }
  const std::string pov_text = read_text_file(scene_pov, std::uintmax_t(1) << 30, "POV-Ray scene");
  AtomicPath pov(dir / "scene_path.pov");  // never committed: removed when done
  write_file_atomically(pov.temp_path(), povray_scene_with_cameras(pov_text, todo_cameras, scene_pov, todo_seconds));
  WorkFolder work(frames, "povray");
  PovrayRenderOptions options;
  options.width = width;
  options.height = height;
  options.input_file = pov.temp_path().filename().string();
  options.frames = static_cast<int>(todo.size());
  options.frames_dir = work.dir();
  options.on_frame = [&](int i, const fs::path& file) { frame_done(todo[std::size_t(i)], file); };
  return render_povray(dir, options).log;
}

}  // namespace

bool complete_png(const fs::path& file, int width, int height) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  char head[24] = {};
  if (!in.read(head, sizeof head)) return false;
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const auto byte = [&](int k) { return std::uint32_t(static_cast<unsigned char>(head[k])); };
  for (int k = 0; k < 8; ++k)
    if (byte(k) != kSignature[k]) return false;
  if (std::string_view(head + 12, 4) != "IHDR") return false;
  const auto be32 = [&](int at) { return byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3); };
  if (be32(16) != std::uint32_t(width) || be32(20) != std::uint32_t(height)) return false;
  char tail[12] = {};
  in.seekg(-12, std::ios::end);
  if (!in.read(tail, sizeof tail)) return false;
  static constexpr unsigned char kEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  for (int k = 0; k < 12; ++k)
    if (static_cast<unsigned char>(tail[k]) != kEnd[k]) return false;
  return true;
}

std::vector<Camera> path_cameras(const Scene& scene, const ViewPath& path, double fps, const fs::path& file) {
  const long long frames = path_frame_count(path, fps, file, "--fps");
  const GroundHeightAt ground = [&](double e, double n) {
    return scene.field ? scene.field->ground.height(e, n) : std::optional<double>();
  };
  std::vector<Camera> cameras;
  cameras.reserve(std::size_t(frames));
  for (long long k = 0; k < frames; ++k)
    cameras.push_back(camera_at_frame(path, k, fps, scene.camera.fov_degrees, ground, file));
  return cameras;
}

PathRenderResult render_path(const fs::path& dir, const PathRenderRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  if (!std::isfinite(request.fps) || request.fps < kMinPathRenderFps || request.fps > kMaxPathRenderFps)
    throw Error("render: --fps " + number_text(request.fps) + ": expected " + number_text(kMinPathRenderFps) + " .. " +
                number_text(kMaxPathRenderFps) + " frames a second");
  if (request.engine == RenderEngine::povray && request.samples != 0)
    throw Error(
        "render: --spp is for --engine embree or blender; povray takes its samples from the scene (its "
        "antialias)");
  // Everything that can be refused is, before the frames folder is made.
  const ViewPath path = read_view_path(request.path);
  path_frame_count(path, request.fps, request.path, "--fps");
  const FolderFiles files(dir);
  if (request.engine == RenderEngine::povray && !fs::is_regular_file(files.povray_scene()))
    throw Error("render: '" + dir.string() + "' has no " + files.povray_scene().filename().string() +
                " (build it with [exports] povray = true)");
  if (request.engine == RenderEngine::blender && find_blender_manifest(dir).empty())
    throw Error("render: '" + dir.string() + "' has no blender/manifest.json (build it with [exports] blender = true)");
  const SceneFolder scene_folder = SceneFolder::open(dir);
  const Scene scene = scene_folder.make_scene();
  const std::vector<Camera> cameras = path_cameras(scene, path, request.fps, request.path);
  const auto [width, height] = folder_image_size(scene_folder.config(), request.width, request.height);
  const long long all = static_cast<long long>(cameras.size());
  const long long first = request.first_frame, count = request.frame_count > 0 ? request.frame_count : all - first;
  if (first < 0 || first >= all || count < 1 || count > all - first)
    throw Error(
        request.path, "",
        (first < 0 || first >= all ? "frame " + std::to_string(first)
                                   : "frames " + std::to_string(first) + " .. " + std::to_string(first + count - 1)) +
            " asked; the path has " + std::to_string(all) + " at " + number_text(request.fps) +
            " frames a second (0 .. " + std::to_string(all - 1) + ")");

  std::error_code ec;
  FramesFolder folder(fs::absolute(request.frames, ec));  // POV-Ray runs in DIR
  remove_stale_temporaries(folder.dir());                 // a killed run's unfinished frames
  remove_stale_temporaries(dir);                          // and its .pov
  PathRenderResult result;
  result.frames = count;
  result.width = width;
  result.height = height;
  const auto frame_file = [&](long long k) { return folder.dir() / path_frame_name(k); };
  std::vector<long long> todo;
  for (long long k = first; k < first + count; ++k) {
    if (complete_png(frame_file(k), width, height)) {
      ++result.skipped;
      folder.keep();
      if (request.on_frame) request.on_frame(result.skipped + result.rendered, result.frames, false);
    } else {
      todo.push_back(k);
    }
  }
  const auto frame_done = [&](long long k, const fs::path& from) {
    if (!from.empty()) publish_frame(from, frame_file(k));
    folder.keep();
    ++result.rendered;
    if (request.on_frame) request.on_frame(result.skipped + result.rendered, result.frames, true);
  };

  if (!todo.empty() && request.engine == RenderEngine::embree) {
    ReferenceOptions options;
    options.width = width;
    options.height = height;
    options.samples_per_pixel = request.samples;
    options.shading = scene_folder.light();  // the light of the folder's LDI pack, as the view's
    const ReferenceFrames traced(scene, cameras[std::size_t(todo.front())].position);  // built once
    for (const long long k : todo) {
      options.camera = cameras[std::size_t(k)];
      options.wind_seconds = double(k) / request.fps;
      write_image(frame_file(k), traced.render(options).image);  // atomically
      frame_done(k, {});
    }
  } else if (!todo.empty() && request.engine == RenderEngine::povray) {
    result.log = render_povray_frames(dir, files.povray_scene(), folder.dir(), cameras, todo, request.fps, width,
                                      height, frame_done);
  } else if (!todo.empty() && request.engine == RenderEngine::blender) {
    // One Blender run: the camera keyframed at every frame of FRAMES/path.blend, the frames to
    // render rendered by Cycles.
    WorkFolder work(folder.dir(), "blender");
    nlohmann::json spec{{"fps", request.fps}, {"cameras", nlohmann::json::array()}, {"render", todo}};
    for (const Camera& c : cameras)
      spec["cameras"].push_back({c.position[0], c.position[1], c.position[2], c.target[0], c.target[1], c.target[2]});
    write_file_atomically(work.dir() / "cameras.json", spec.dump());
    BlenderRenderOptions options;
    options.width = width;
    options.height = height;
    options.samples = request.samples;
    options.blend_path = folder.dir() / "path.blend";
    options.cameras_file = work.dir() / "cameras.json";
    options.frames_dir = work.dir();
    options.log = folder.dir() / "blender.log";
    options.on_frame = [&](int k, const fs::path& file) { frame_done(k, file); };
    const BlenderRenderResult blender = render_blender(dir, options);
    result.blend = blender.blend;
    result.log = blender.log;
  }
  for (long long k = first; k < first + count; ++k)
    if (!complete_png(frame_file(k), width, height))
      throw Error(frame_file(k), "",
                  "the " + std::string(to_string(request.engine)) + " run ended without this frame" +
                      (result.log.empty() ? std::string() : "; log " + result.log.string()));
  if (count == all && write_frames_movie(folder.dir(), kPathFramePattern, request.fps, folder.dir() / "path.mp4"))
    result.movie = folder.dir() / "path.mp4";
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace wangscape
