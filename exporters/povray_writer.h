// POV-Ray export: a Scene as a folder POV-Ray 3.7 renders with `povray scene.ini` run from
// that folder. Files:
//   scene.pov       camera, sun (parallel light_source), sky_sphere, fog, ground texture,
//                   radiosity switch, header comment with the georeference; includes the rest
//   scene.ini       size, antialiasing, threads, Library_Path (POV-Ray resolves includes
//                   against the current directory and the library paths, not the .pov's folder)
//   models.inc      each model variant declared once as `mesh2`, named by povray_model_names:
//                   copies of a mesh2 share its data, so a million flowers cost little memory;
//                   materials are one uv-mapped palette texture (a texture_list would be
//                   copied with every instance), except for a model whose materials map images:
//                   a texture_list, an image_map per such material through the model's uvs
//   map_NAME.png    those images (material_textures: base colour in, alpha 0 or 255)
//   terrain.inc     the terrain as one mesh2 (Terrain), absent when the scene has no terrain
//   instances.inc   one `object { Sunflower_3 rotate ... scale ... translate ... }` per instance,
//                   closed by a comment with the count
//   ground.png      with a [ground] look: Scene::ground_texture, an image_map over the terrain
// Axes: ENU (x east, y north, z up) becomes POV (x east, y up, z north). Swapping y and z is a
// reflection, which is exactly what POV's left-handed axes need: the picture is not mirrored.
// Numbers are written with std::to_chars (locale-independent).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "exporters/scene_writer.h"
#include "scene/scene.h"

namespace wangscape {

class EncodedGround;  // export_support.h

// The POV-Ray export's entry file, which scene.ini names and POV-Ray renders (a scene folder's
// readers ask folder/folder_files.h for it).
inline constexpr char kPovraySceneFile[] = "scene.pov";

struct PovrayExportOptions {
  // Folder the scene will finally live in, written as the ini's Library_Path (the pipeline
  // writes into a staging folder first, then renames it). Empty: the folder written to.
  std::filesystem::path final_dir;
  // Called now and then with the number of instances written so far.
  std::function<void(std::uint64_t written)> on_instances;
  // The build's encoded ground.png (export_support.h); null: this writer encodes its own.
  std::shared_ptr<const EncodedGround> ground;
};

struct PovrayExportStats {
  std::uint64_t instances = 0;
  std::uint64_t instance_bytes = 0;  // size of instances.inc
  std::uint64_t total_bytes = 0;     // all files
};

// The POV-Ray files above as a streaming writer into `dir` (which must exist): the files that
// do not depend on the instances are written when it is made, instances.inc as batches come,
// scene.pov (which records the count) at finish(). Every file stays under a temporary name
// until finish() renames them all, so a failure leaves none of them. Throws Error naming the
// file at fault.
class PovrayWriter final : public SceneWriter {
 public:
  PovrayWriter(const Scene& scene, const std::filesystem::path& dir, const PovrayExportOptions& options = {});
  ~PovrayWriter() override;
  void append(const InstanceBatch& batch) override;
  void finish(const StreamTotals& totals) override;
  const PovrayExportStats& stats() const;  // complete after finish()

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A PovrayWriter over the scene's own stream: writes the whole POV-Ray scene into `dir`.
PovrayExportStats write_povray_scene(const Scene& scene, const std::filesystem::path& dir,
                                     const PovrayExportOptions& options = {});

// The camera and sun blocks of scene.pov (batch renders write one per still over a shared
// scene folder, so a new viewpoint or hour costs no new placement).
std::string povray_camera_and_sun(const Camera& camera, const Sun& sun);

// The wind's lean of a plant at (E, N) at Wind_Time seconds, in degrees, as two POV-Ray
// functions, Wind_East(E, N) and Wind_North(E, N), that scene.pov declares and instances.inc
// calls (scene/wind.h: the same sum of sines every engine evaluates). Wind_Time is 0 unless
// declared before.
std::string povray_wind_functions(const WindField& wind);

// `scene_pov` (a folder's scene.pov, read from `file`, which errors name) with its camera and sun
// blocks replaced by povray_camera_and_sun's: a still from another camera under another sun.
// Throws Error naming `file` when it has no such blocks.
std::string povray_scene_with_camera_and_sun(const std::string& scene_pov, const Camera& camera, const Sun& sun,
                                             const std::filesystem::path& file);

// `scene_pov` (a folder's scene.pov, read from `file`, which errors name) with its camera block
// replaced: one camera, or with several an animation's, frame_number k (POV-Ray's +KFI0
// +KFF<N-1>) looking from cameras[k].position at cameras[k].target, every frame with the first
// camera's field of view. The sun and everything else stay. Throws Error naming `file` when it
// has no camera block, and for no camera. `seconds`, when given, one per camera: the wind's
// time of each frame (Wind_Time; a scene without [wind] ignores it).
std::string povray_scene_with_cameras(const std::string& scene_pov, const std::vector<Camera>& cameras,
                                      const std::filesystem::path& file, const std::vector<double>& seconds = {});

// `path` in double quotes for a POV-Ray ini value or command-line option (POV-Ray rejoins its
// arguments and splits them at spaces; an unquoted ';' starts an ini comment). Throws Error
// naming the path when it holds a control character (a newline would add an ini line) or a
// '"', which POV-Ray cannot quote.
std::string povray_quoted_path(const std::filesystem::path& path);

// POV-Ray's names of the model variants in models.inc, one per model, from each model's own name
// as an identifier, first letter capitalised ("sunflower_3" -> Sunflower_3, a species' grass
// "meadow_grass_2" -> Meadow_grass_2, a proxy "sunflower_3 proxy" -> Sunflower_3_proxy), so a
// user editing the scene knows which is which; a name used twice gets the variant's index.
std::vector<std::string> povray_model_names(const std::vector<Mesh>& models);

// Formats instances as POV-Ray objects into a buffer and writes it out in large blocks;
// the hot loop of the exporter (see bench/povray_bench.cpp).
class PovrayInstanceWriter {
 public:
  // `model_names`: povray_model_names of the models the instances' variants index. `sway`: each
  // instance leans by the scene's wind functions (Wind_North, Wind_East of scene.pov) at its place.
  PovrayInstanceWriter(std::ostream& out, const std::vector<std::string>& model_names, bool sway = false);
  ~PovrayInstanceWriter() { flush(); }
  PovrayInstanceWriter(const PovrayInstanceWriter&) = delete;
  PovrayInstanceWriter& operator=(const PovrayInstanceWriter&) = delete;

  void write(const InstanceBatch& batch);
  // Writes what is buffered to the stream (the caller checks the stream's state).
  void flush();
  std::uint64_t instances() const { return instances_; }
  std::uint64_t bytes() const { return bytes_; }

 private:
  std::ostream& out_;
  std::vector<std::string> object_prefixes_;  // per variant: "object{NAME"
  bool sway_ = false;
  std::string buffer_;
  std::uint64_t instances_ = 0;
  std::uint64_t bytes_ = 0;
};

}  // namespace wangscape
