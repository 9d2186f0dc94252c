#include "renders/external/blender_render.h"

#include <cstdlib>
#include <functional>
#include <vector>

#include "core/atomic_file.h"
#include "exporters/zip_writer.h"
#include "folder/folder_files.h"
#include "renders/external/child_process.h"
#include "templates/blender_addon.h"

namespace wangscape {

namespace {

// Runs inside Blender. Arguments after "--": add-on zip, manifest, .blend path ("" = do
// not save), image path, width, height, samples, threads (0 = keep the manifest's), and for
// frames the cameras file and the frames folder (BlenderRenderOptions).
constexpr const char* kRenderScript = R"py(
import os, sys, time
args = sys.argv[sys.argv.index("--") + 1:]
addon_zip, manifest, blend_path, image_path = args[:4]
width, height, samples, threads = (int(a) for a in args[4:8])
sys.path.insert(0, addon_zip)  # the add-on zip is an importable package archive
import bpy
import wangscape_import
wangscape_import.register()
for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.cameras, bpy.data.lights, bpy.data.materials):
    for item in list(collection):
        collection.remove(item)
start = time.perf_counter()
result = bpy.ops.import_scene.wangscape(filepath=manifest)
if "FINISHED" not in result:
    raise RuntimeError("wangscape-blender: error: importing %s failed" % manifest)
print("wangscape-blender: imported %s in %.3f s" % (manifest, time.perf_counter() - start))
scene = bpy.context.scene
if width > 0: scene.render.resolution_x = width
if height > 0: scene.render.resolution_y = height
if samples > 0: scene.cycles.samples = samples
if threads > 0:
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
cameras_file, frames_dir = (args[8:10] + ["", ""])[:2]
if cameras_file:
    # The camera keyframed at every frame of the path (frames from 0), turned as the add-on
    # turns it: looking down -z at the target, its y up.
    import json
    from mathutils import Vector
    with open(cameras_file) as f:
        spec = json.load(f)
    camera = scene.camera
    camera.rotation_mode = "QUATERNION"
    scene.frame_start, scene.frame_end = 0, len(spec["cameras"]) - 1
    fps = float(spec["fps"])
    scene.render.fps = max(1, round(fps))
    scene.render.fps_base = scene.render.fps / fps
    for k, c in enumerate(spec["cameras"]):
        eye, target = Vector(c[0:3]), Vector(c[3:6])
        camera.location = eye
        camera.rotation_quaternion = (target - eye).to_track_quat("-Z", "Y")
        camera.keyframe_insert("location", frame=k)
        camera.keyframe_insert("rotation_quaternion", frame=k)
    for curve in camera.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"
if blend_path:
    bpy.ops.wm.save_as_mainfile(filepath=blend_path, check_existing=False)
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.color_depth = "8"
scene.render.use_file_extension = False  # the temporary's name is not the image's
if cameras_file:
    # Each frame asked, as f<k>.png once complete (renamed from a partial file).
    for k in spec["render"]:
        scene.frame_set(k)
        partial = os.path.join(frames_dir, "f%d.partial" % k)
        scene.render.filepath = partial
        start = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        if not os.path.exists(partial):
            raise RuntimeError("wangscape-blender: error: Cycles wrote no image for frame %d" % k)
        os.replace(partial, os.path.join(frames_dir, "f%d.png" % k))
        print("wangscape-blender: rendered frame %d in %.3f s" % (k, time.perf_counter() - start), flush=True)
    sys.exit(0)
scene.render.filepath = image_path
start = time.perf_counter()
bpy.ops.render.render(write_still=True)
if not os.path.exists(image_path):
    raise RuntimeError("wangscape-blender: error: Cycles wrote no image to %s" % image_path)
print("wangscape-blender: rendered %s in %.3f s" % (image_path, time.perf_counter() - start))
)py";

std::string program_wanted(const std::string& executable) {
  if (!executable.empty()) return executable;
  const char* env = std::getenv("WANGSCAPE_BLENDER");
  return (env && *env) ? env : "blender";
}

}  // namespace

std::filesystem::path find_blender(const std::string& executable) { return find_program(program_wanted(executable)); }

std::filesystem::path find_blender_manifest(const std::filesystem::path& dir) {
  for (const auto& candidate : {FolderFiles(dir).blender() / "manifest.json", dir / "manifest.json"}) {
    if (std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return {};
}

BlenderRenderResult render_blender(const std::filesystem::path& dir_in, const BlenderRenderOptions& options) {
  std::error_code ec;
  const auto dir = std::filesystem::absolute(dir_in, ec);
  BlenderRenderResult result;
  result.manifest = find_blender_manifest(dir);
  if (result.manifest.empty()) {
    throw Error("render: '" + dir_in.string() +
                "' has no blender/manifest.json (write one with `wangscape build` and [exports] blender = true)");
  }
  const auto blender = find_blender(options.executable);
  if (blender.empty()) {
    throw Error("render: Blender ('" + program_wanted(options.executable) +
                "') is not installed or not in PATH; install it (apt install blender) or set WANGSCAPE_BLENDER");
  }

  // The export normally carries the add-on zip; write the embedded one if it does not.
  const auto addon_zip = result.manifest.parent_path() / "wangscape_import.zip";
  if (!std::filesystem::is_regular_file(addon_zip)) {
    write_file_atomically(addon_zip, blender_addon_zip());
  }

  const bool frames = !options.cameras_file.empty();
  result.image = dir / options.image_name;
  result.log = options.log.empty() ? dir / "blender.log" : std::filesystem::absolute(options.log, ec);
  AtomicPath image(result.image);
  const std::filesystem::path blend_path =
      options.blend_path.empty() ? dir / "scene.blend" : std::filesystem::absolute(options.blend_path, ec);
  AtomicPath blend(blend_path);
  AtomicPath log(result.log);
  std::filesystem::remove(log.temp_path(), ec);
  // A script file rather than --python-expr: on errors Blender echoes an expression whole.
  AtomicPath script(dir / "blender_render.py");
  write_file_atomically(script.temp_path(), kRenderScript);

  std::vector<std::string> argv = {blender.string(),
                                   "-b",
                                   "--factory-startup",
                                   "--python-exit-code",
                                   "1",
                                   "--python",
                                   script.temp_path().string(),
                                   "--",
                                   addon_zip.string(),
                                   result.manifest.string(),
                                   options.save_blend ? blend.temp_path().string() : std::string(),
                                   image.temp_path().string(),
                                   std::to_string(options.width),
                                   std::to_string(options.height),
                                   std::to_string(options.samples),
                                   std::to_string(options.threads)};
  if (frames) {
    argv.push_back(std::filesystem::absolute(options.cameras_file, ec).string());
    argv.push_back(std::filesystem::absolute(options.frames_dir, ec).string());
  }
  const auto hand_over_frames = [&] {
    for (const auto& [k, file] : numbered_frames(options.frames_dir))
      if (options.on_frame) options.on_frame(k, file);
  };
  ChildExit exit;
  try {
    exit = run_logged(argv, log.temp_path(), {}, frames ? std::function<void()>(hand_over_frames) : nullptr);
  } catch (const std::exception& e) {
    throw Error(std::string("render: ") + e.what());
  }
  if (frames) hand_over_frames();
  result.seconds = exit.seconds;
  const bool log_written = std::filesystem::exists(log.temp_path());
  if (log_written) log.commit();
  const bool exited_ok = exit.exited && exit.status == 0;
  if (!exited_ok || (!frames && !std::filesystem::exists(image.temp_path())) ||
      (options.save_blend && !std::filesystem::exists(blend.temp_path()))) {
    throw Error("render: Blender " + exit.describe() + " importing and rendering '" + result.manifest.string() + "'" +
                (exited_ok ? " without writing the image or .blend" : "") + "; log " + result.log.string() +
                (log_written ? ", last lines:" + last_log_lines(result.log, 8) : ""));
  }
  if (options.save_blend) {
    blend.commit();
    result.blend = blend_path;
  }
  if (frames) {
    result.image.clear();
    return result;
  }
  image.commit();
  return result;
}

}  // namespace wangscape
