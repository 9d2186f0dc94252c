// Durable publishing (issue 41): the flushes themselves, and their errors naming the file. That
// every publisher flushes before and after its rename is checked from the system calls, under
// strace (tests/cli/durable_publish.sh).
#include "core/durable_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using wangscape::testing::fresh_folder;

using wangscape::testing::error_of;

TEST(DurableFile, FlushesFilesFoldersAndTrees) {
  const fs::path dir = fresh_folder("durable_tree");
  fs::create_directories(dir / "a" / "b");
  std::ofstream(dir / "a" / "b" / "x.bin") << "data";
  std::ofstream(dir / "y.txt") << "text";
  fs::create_symlink("/nonexistent/target", dir / "dangling");  // not followed
  EXPECT_NO_THROW(sync_file(dir / "y.txt"));
  EXPECT_NO_THROW(sync_folder(dir));
  EXPECT_NO_THROW(sync_tree(dir));
  fs::remove_all(dir);
}

TEST(DurableFile, ErrorsNameTheFileOrFolder) {
  const fs::path dir = fresh_folder("durable_errors");
  EXPECT_EQ(error_of([&] { sync_file(dir / "missing.bin"); }),
            (dir / "missing.bin").string() + ": cannot open the file to flush it to disk: No such file or directory");
  EXPECT_EQ(error_of([&] { sync_folder(dir / "missing"); }),
            (dir / "missing").string() + ": cannot open the folder to flush it to disk: No such file or directory");
  EXPECT_EQ(error_of([&] { sync_file(-1, dir / "x.bin"); }),
            (dir / "x.bin").string() + ": cannot flush the file to disk: Bad file descriptor");
  EXPECT_NE(error_of([&] { sync_tree(dir / "missing"); }).find((dir / "missing").string()), std::string::npos);
  fs::remove_all(dir);
}

TEST(DurableFile, AtomicFileStillPublishesIntoTheCurrentFolder) {
  const fs::path dir = fresh_folder("durable_atomic");
  write_file_atomically(dir / "out.txt", "hello\n");
  std::ifstream in(dir / "out.txt");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "hello");
  // A relative target: its folder is the working folder ("" as the parent is ".").
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  write_file_atomically("relative.txt", "x");
  fs::current_path(here);
  EXPECT_TRUE(fs::is_regular_file(dir / "relative.txt"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wangscape
