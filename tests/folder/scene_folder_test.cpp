// The scene folder: placement runs once for every export together, the folder holds only
// final files, a rebuild replaces the folder whole, and a failure leaves the old one as it was.
#include "folder/scene_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "tests/blender/test_scene.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("wangscape_scene_folder_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

constexpr ExportsConfig kAllExports{true, true, true};

// A test scene whose stream counts how often it runs.
Scene counted_scene(std::uint64_t instances, int& runs) {
  Scene scene = testing::make_test_scene(instances, 8, 20.0f, 700);
  const InstanceStream whole = scene.instances;
  scene.instances = [whole, &runs](const InstanceSink& sink) {
    ++runs;
    whole(sink);
  };
  return scene;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.push_back(fs::relative(entry.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(SceneFolder, EveryExportFromOnePlacementPass) {
  int runs = 0;
  const Scene scene = counted_scene(5000, runs);
  const auto out = scratch("all");
  const auto summary = SceneFolder::write(scene, {kAllExports, "name = \"t\"\n", {}}, out);
  EXPECT_EQ(runs, 1);
  EXPECT_EQ(summary.instances, 5000u);
  std::uint64_t sum = 0;
  for (const auto n : summary.per_variant) sum += n;
  EXPECT_EQ(sum, 5000u);
  for (const char* file : {"scene.pov", "scene.ini", "models.inc", "terrain.inc", "instances.inc", "scene.glb",
                           "scene.toml", "blender/manifest.json", "blender/instances_x.f32"})
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  // Only final files: no temporary or hidden file of any writer is published.
  for (const auto& name : names_in(out)) {
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_NE(fs::path(name).filename().string().front(), '.') << name;
  }
  // Nothing is left beside the folder either.
  for (const auto& entry : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".all."), std::string::npos) << entry.path();
}

TEST(SceneFolder, TotalsReachThePovrayHeader) {
  int runs = 0;
  const auto out = scratch("header");
  SceneFolder::write(counted_scene(1234, runs), {{true, false, false}, "", {}}, out);
  std::ifstream pov(out / "scene.pov");
  const std::string text((std::istreambuf_iterator<char>(pov)), {});
  EXPECT_NE(text.find("//   instances: 1234\n"), std::string::npos);
}

TEST(SceneFolder, RebuildReplacesTheWholeFolder) {
  int runs = 0;
  const auto out = scratch("rebuild");
  SceneFolder::write(counted_scene(100, runs), {kAllExports, "", {}}, out);
  SceneFolder::write(counted_scene(100, runs), {{true, false, false}, "", {}}, out);  // no Blender, no glTF now
  EXPECT_FALSE(fs::exists(out / "scene.glb"));
  EXPECT_FALSE(fs::exists(out / "blender"));
  EXPECT_TRUE(fs::exists(out / "scene.pov"));
}

TEST(SceneFolder, RefusesAFolderThatIsNotASceneFolder) {
  int runs = 0;
  const auto out = scratch("foreign");
  fs::create_directories(out);
  std::ofstream(out / "notes.txt") << "mine";
  EXPECT_THROW(SceneFolder::write(counted_scene(10, runs), {kAllExports, "", {}}, out), Error);
  EXPECT_EQ(names_in(out), std::vector<std::string>{"notes.txt"});
  EXPECT_EQ(runs, 0);
}

TEST(SceneFolder, FailureLeavesTheEarlierBuildAsItWas) {
  int runs = 0;
  const auto out = scratch("failure");
  SceneFolder::write(counted_scene(100, runs), {kAllExports, "first", {}}, out);
  const auto before = names_in(out);
  Scene failing = counted_scene(3000, runs);
  failing.instances = testing::failing_at_batch(failing.instances, 2);
  EXPECT_THROW(SceneFolder::write(failing, {kAllExports, "second", {}}, out), Error);
  EXPECT_EQ(names_in(out), before);
  std::ifstream toml(out / "scene.toml");
  const std::string text((std::istreambuf_iterator<char>(toml)), {});
  EXPECT_EQ(text, "first");
  for (const auto& entry : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".failure."), std::string::npos) << entry.path();
}

// The folder remembers where the scene file's relative paths resolve: loading it again finds
// the same mask as the file did, wherever the folder is.
TEST(SceneFolder, LoadingTheFolderResolvesPathsAsTheSceneFileDid) {
  int runs = 0;
  const auto out = scratch("reload");
  const fs::path base = out.parent_path() / "scene_source";
  const std::string text = "name = \"reload\"\n[masks]\nmask = \"masks/field.png\"\n";
  SceneFolder::write(counted_scene(10, runs), {{false, false, false}, text, base}, out);
  const auto config_of = [](const fs::path& dir) {
    return SceneFolder::open(dir, SceneFolder::Parts::scene_file).config();
  };
  const SceneConfig again = config_of(out);
  EXPECT_EQ(again.masks.mask, fs::absolute(base).lexically_normal() / "masks/field.png");
  EXPECT_EQ(again.name, "reload");
  EXPECT_EQ(again.source, out / "scene.toml");
  // Without the base file (a folder from elsewhere), paths resolve against the folder itself.
  fs::remove(out / "scene_base.txt");
  EXPECT_EQ(config_of(out).masks.mask, out / "masks/field.png");
  EXPECT_THROW(config_of(out / "missing"), Error);
}

// One message for each way a folder can be unusable, each naming the file at fault.
TEST(SceneFolder, OpeningSaysWhyAFolderIsUnusable) {
  const auto refusal = [](const fs::path& dir, SceneFolder::Parts parts) {
    try {
      SceneFolder::open(dir, parts);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("opened");
  };
  const auto out = scratch("unusable");
  EXPECT_NE(refusal(out, SceneFolder::Parts::scene_file).find("no such scene folder"), std::string::npos);
  fs::create_directories(out);
  const std::string no_scene = refusal(out, SceneFolder::Parts::scene_file);
  EXPECT_NE(no_scene.find(FolderFiles(out).scene_file().string() + ": missing"), std::string::npos) << no_scene;
  int runs = 0;
  SceneFolder::write(counted_scene(10, runs), {{false, false, false}, "name = \"t\"\n", {}}, out);
  EXPECT_EQ(SceneFolder::open(out, SceneFolder::Parts::scene_file).config().name, "t");
  const std::string no_pack = refusal(out, SceneFolder::Parts::pack);
  EXPECT_NE(no_pack.find(FolderFiles(out).pack().string() + ": missing"), std::string::npos) << no_pack;
}

}  // namespace
}  // namespace wangscape
