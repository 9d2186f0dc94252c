#include "exporters/scene_folder.h"

#include "exporters/folder_state.h"

#include <fcntl.h>  // AT_FDCWD; renameat2 and RENAME_EXCHANGE come from <cstdio> (glibc 2.28+, _GNU_SOURCE)
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/atomic_file.h"
#include "core/durable_file.h"
#include "core/run_cleanup.h"
#include "core/text_file.h"
#include "exporters/blender_export.h"
#include "exporters/export_support.h"
#include "exporters/folder_state.h"
#include "exporters/gltf_writer.h"
#include "exporters/povray_writer.h"
#include "exporters/scene_writer.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

// One line: the absolute folder the relative paths of scene.toml resolve against.
constexpr const char* kSceneBaseFile = "scene_base.txt";

void say(const SceneFolderObserver& observer, const std::string& message) {
  if (observer.stage) observer.stage(message);
}

// The folder a build stages into and the one an old build is moved to during the swap.
fs::path sibling(const fs::path& out_dir, const char* role) {
  std::string name(1, '.');  // appended piecewise: GCC 12 warns falsely on "." + ...
  name += out_dir.filename().string();
  name += '.';
  name += role;
  name += '-';
  name += std::to_string(::getpid());
  return out_dir.parent_path() / name;
}

// Replaces out_dir by staging: with one rename when out_dir does not exist, else with one
// exchange of the two folders (renameat2 RENAME_EXCHANGE), so a reader, or a kill at any moment,
// finds the old folder or the new one, never none; the old build, now at the staging name, is
// removed after. Where the filesystem cannot exchange (EINVAL: not supported there), out_dir is
// renamed aside first and the new one renamed in, which the observer is told: in between, for a
// moment, there is no folder (a run killed there puts the old one back on the next write).
// Durably (core/durable_file.h): every file and folder of staging is flushed to disk before the
// swap, the folder holding out_dir after it, so a power cut leaves the old build or the new one.
void publish(const fs::path& staging, const fs::path& out_dir, const SceneFolderObserver& observer) {
  sync_tree(staging);
  auto uninterrupted = hold_run_cleanup();  // an interrupt waits until the swap is done
  std::error_code ec;
  if (fs::exists(out_dir, ec)) {
    if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, out_dir.c_str(), RENAME_EXCHANGE) == 0) {
      uninterrupted.unlock();  // staging (still a registered temporary) now holds the old build
      sync_folder(out_dir.parent_path());
      fs::remove_all(staging, ec);
      unregister_temporary(staging);
      return;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
      throw Error(out_dir, "", std::string("cannot swap the new build in: ") + std::strerror(errno));
    if (observer.warning)
      observer.warning("this filesystem cannot exchange two folders at once (" + std::string(std::strerror(errno)) +
                       "); replacing " + out_dir.string() + " with two renames");
    const fs::path old = sibling(out_dir, "old");
    fs::remove_all(old, ec);
    fs::rename(out_dir, old, ec);
    if (ec) throw Error(out_dir, "", "cannot move the earlier build aside: " + ec.message());
    fs::rename(staging, out_dir, ec);
    if (ec) {
      std::error_code restore;
      fs::rename(old, out_dir, restore);
      throw Error(out_dir, "", "cannot move the new build into place: " + ec.message());
    }
    unregister_temporary(staging);
    register_temporary(old);
    uninterrupted.unlock();
    sync_folder(out_dir.parent_path());
    fs::remove_all(old, ec);
    unregister_temporary(old);
    return;
  }
  fs::rename(staging, out_dir, ec);
  if (ec) throw Error(out_dir, "", "cannot create the scene folder: " + ec.message());
  unregister_temporary(staging);
  sync_folder(out_dir.parent_path());
}

}  // namespace

void check_scene_folder_target(const fs::path& out_dir_in) {
  if (out_dir_in.empty()) throw Error("the output folder is empty: give a folder name");
  const auto out_dir = fs::absolute(out_dir_in).lexically_normal();
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec)) throw Error(out_dir, "", "exists and is not a folder");
  if (fs::is_empty(out_dir, ec) || fs::is_regular_file(out_dir / "scene.toml", ec)) return;
  throw Error(out_dir, "",
              "exists and is not a scene folder (it has no scene.toml); give a new or empty folder, or an earlier "
              "build's");
}

SceneFolderSummary write_scene_folder(const Scene& scene, const ExportsConfig& exports, const std::string& scene_text,
                                      const fs::path& out_dir_in, const SceneFolderObserver& observer,
                                      const fs::path& scene_base_dir, const StagedWriter& also_write) {
  const auto start = std::chrono::steady_clock::now();
  check_scene_folder_target(out_dir_in);
  auto out_dir = fs::absolute(out_dir_in).lexically_normal();
  if (out_dir.filename().empty()) out_dir = out_dir.parent_path();

  std::error_code ec;
  // The parent folders this build makes, nearest first: a build that fails removes them again.
  std::vector<fs::path> made;
  for (fs::path p = out_dir.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    made.push_back(p);
    if (p == p.parent_path()) break;
  }
  const auto remove_made = [&] {
    for (const fs::path& p : made) fs::remove(p, ec);  // only while empty
  };
  fs::create_directories(out_dir.parent_path(), ec);
  remove_stale_temporaries(out_dir.parent_path());
  const fs::path staging = sibling(out_dir, "partial");
  fs::remove_all(staging, ec);
  register_temporary(staging);
  if (!fs::create_directory(staging, ec) || ec) {
    unregister_temporary(staging);
    const std::string why = ec.message();
    remove_made();
    throw Error(staging, "", "cannot create the staging folder beside the output folder: " + why);
  }

  SceneFolderSummary summary;
  try {
    std::unique_ptr<PovrayWriter> povray;
    std::unique_ptr<BlenderWriter> blender;
    std::unique_ptr<GltfWriter> gltf;
    std::vector<SceneWriter*> writers;
    std::vector<std::string> names;
    // The ground is encoded once, here, for every writer that writes or embeds it.
    const auto ground = scene.ground_texture ? std::make_shared<const EncodedGround>(scene.ground_texture) : nullptr;
    if (exports.povray) {
      PovrayExportOptions options;
      options.final_dir = out_dir;
      options.ground = ground;
      povray = std::make_unique<PovrayWriter>(scene, staging, options);
      writers.push_back(povray.get());
      names.emplace_back("POV-Ray");
    }
    if (exports.blender) {
      BlenderExportOptions options;
      options.ground = ground;
      blender = std::make_unique<BlenderWriter>(scene, staging / "blender", options);
      writers.push_back(blender.get());
      names.emplace_back("Blender");
    }
    if (exports.gltf) {
      GltfOptions options;
      options.ground = ground;
      gltf = std::make_unique<GltfWriter>(scene, staging / "scene.glb", options);
      writers.push_back(gltf.get());
      names.emplace_back("glTF");
    }
    // The tiles that receive flowers, for the folder's readers (folder_state.h): collected from
    // the writers' pass, or from a pass of their own when nothing else places the field.
    std::optional<PlacedTileCollector> placed;
    if (scene.field) placed.emplace(*scene.field);
    if (!writers.empty()) {
      std::string list;
      for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
      say(observer, "placing flowers and writing " + list);
      const Extent& area = scene.field_area;
      const auto on_batch = [&](const InstanceBatch& batch) {
        if (placed) placed->add(batch);
        if (!observer.placing || batch.empty() || !(area.height() > 0)) return;
        observer.placing(std::clamp((batch.y.back() - area.min_y) / area.height(), 0.0, 1.0));
      };
      const StreamTotals totals = run_scene_stream(scene, writers, on_batch);
      summary.instances = totals.instances;
      summary.per_variant = totals.per_variant;
      if (scene.last_placement) summary.field = *scene.last_placement;
      if (observer.placing) observer.placing(1.0);
    }
    if (povray) summary.povray_bytes = povray->stats().total_bytes;
    if (scene.field) {
      const PlacedTiles tiles = writers.empty() ? place_tiles(*scene.field) : placed->result();
      write_folder_state(staging, scene_text, scene, tiles);
    }
    if (also_write) also_write(staging);
    write_file_atomically(staging / "scene.toml", scene_text);
    if (!scene_base_dir.empty())
      write_file_atomically(staging / kSceneBaseFile, fs::absolute(scene_base_dir).lexically_normal().string() + "\n");
    publish(staging, out_dir, observer);
    // The folders this build made hold their entries durably too (the nearest is out_dir's
    // parent, flushed by publish).
    for (const fs::path& p : made) sync_folder(p.parent_path());
  } catch (...) {
    fs::remove_all(staging, ec);
    unregister_temporary(staging);
    remove_made();
    throw;
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

SceneFolderSummary build_scene_folder(const SceneConfig& config, const fs::path& out_dir,
                                      const SceneFolderObserver& observer) {
  // Refuse an unusable folder before the (long) scene assembly.
  check_scene_folder_target(out_dir);
  const Scene scene = make_scene(config, observer.stage);
  return write_scene_folder(scene, config.exports, config.text, out_dir, observer, config.base_dir);
}

SceneConfig load_scene_folder_config(const fs::path& dir) {
  const fs::path file = dir / "scene.toml";
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw Error(file, "", "is missing: give a folder written by `wangscape build`");
  const std::string text = read_text_file(file, kMaxSceneFileBytes, "scene file");
  fs::path base = dir;
  if (fs::is_regular_file(dir / kSceneBaseFile, ec)) {
    std::string line = read_text_file(dir / kSceneBaseFile, 1 << 16, "scene base file");
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (!line.empty()) base = line;
  }
  return parse_scene_config(text, file, base);
}

}  // namespace wangscape
