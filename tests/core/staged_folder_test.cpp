// A folder written whole or not at all (core/staged_folder.h): nothing of a staging folder that
// was not published stays behind, not even the parent folders it made; publishing replaces an
// earlier folder whole.
#include "core/staged_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using wangscape::testing::fresh_folder;

TEST(StagedFolder, AFolderNotPublishedLeavesNothingBehind) {
  const fs::path dir = fresh_folder("staged_abandoned");
  {
    StagedFolder staged(dir / "a" / "b" / "out");
    EXPECT_EQ(staged.target(), dir / "a" / "b" / "out");
    EXPECT_EQ(staged.path().parent_path(), dir / "a" / "b");
    std::ofstream(staged.path() / "half") << "written";
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "the staging folder and the parents it made are gone";
  fs::remove_all(dir);
}

TEST(StagedFolder, PublishingCreatesOrReplacesTheFolderWhole) {
  const fs::path dir = fresh_folder("staged_published");
  for (const char* file : {"first", "second"}) {
    StagedFolder staged(dir / "out");
    std::ofstream(staged.path() / file) << file;
    staged.publish();
  }
  EXPECT_FALSE(fs::exists(dir / "out" / "first")) << "the earlier folder was replaced whole";
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "second"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "no staging folder left";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wangscape
