// Stale temporaries of dead runs are removed, a live run's never; user text is escaped.
#include "core/run_cleanup.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <fstream>
#include <string>

#include "core/atomic_file.h"
#include "core/printable.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using wangscape::testing::fresh_folder;

// A pid no process has: the highest below pid_max that kill(pid, 0) reports gone.
pid_t dead_pid() {
  long pid_max = 32768;
  std::ifstream("/proc/sys/kernel/pid_max") >> pid_max;
  auto pid = static_cast<pid_t>(pid_max - 1);
  while (::kill(pid, 0) == 0 || errno != ESRCH) --pid;
  return pid;
}

void touch(const fs::path& path) { std::ofstream(path) << "x"; }

TEST(RunCleanup, RemovesWhatDeadRunsLeftAndKeepsLiveOnes) {
  const fs::path dir = fresh_folder("run_cleanup_stale");
  const std::string dead = std::to_string(dead_pid()), live = std::to_string(::getppid()),
                    self = std::to_string(::getpid());
  touch(dir / (".tmp-" + dead + "-a.csv"));
  touch(dir / (".tmp-" + live + "-b.csv"));
  touch(dir / (".tmp-" + self + "-c.csv"));
  touch(dir / ".tmp-notapid-d.csv");
  // AtomicFile's names since issue 25: the pid last, so the extension is not the target's.
  touch(dir / (".e.csv.tmp-" + dead));
  touch(dir / (".f.csv.tmp-" + live));
  fs::create_directory(dir / (".out.partial-" + dead));
  touch(dir / (".out.partial-" + dead) / "scene.pov");
  fs::create_directory(dir / (".kept.partial-" + live));
  // An earlier build moved aside by a swap cut short: it is all there is of 'gone', so it returns.
  fs::create_directory(dir / (".gone.old-" + dead));
  touch(dir / (".gone.old-" + dead) / "scene.toml");
  // Beside a finished build, the old one is removed.
  fs::create_directory(dir / "done");
  fs::create_directory(dir / (".done.old-" + dead));

  remove_stale_temporaries(dir);

  EXPECT_FALSE(fs::exists(dir / (".tmp-" + dead + "-a.csv")));
  EXPECT_TRUE(fs::exists(dir / (".tmp-" + live + "-b.csv")));
  EXPECT_TRUE(fs::exists(dir / (".tmp-" + self + "-c.csv")));
  EXPECT_TRUE(fs::exists(dir / ".tmp-notapid-d.csv"));
  EXPECT_FALSE(fs::exists(dir / (".e.csv.tmp-" + dead)));
  EXPECT_TRUE(fs::exists(dir / (".f.csv.tmp-" + live)));
  EXPECT_FALSE(fs::exists(dir / (".out.partial-" + dead)));
  EXPECT_TRUE(fs::exists(dir / (".kept.partial-" + live)));
  EXPECT_TRUE(fs::exists(dir / "gone" / "scene.toml"));
  EXPECT_FALSE(fs::exists(dir / (".gone.old-" + dead)));
  EXPECT_TRUE(fs::exists(dir / "done"));
  EXPECT_FALSE(fs::exists(dir / (".done.old-" + dead)));
  fs::remove_all(dir);
}

TEST(RunCleanup, AtomicFileClearsItsFolderFirst) {
  const fs::path dir = fresh_folder("run_cleanup_atomic");
  const fs::path stale = dir / (".tmp-" + std::to_string(dead_pid()) + "-old.txt");
  touch(stale);
  write_file_atomically(dir / "new.txt", "hello");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(dir / "new.txt"));
  // Its temporary is no file a reader of the folder takes for content: not a .csv (issue 25).
  {
    AtomicFile file(dir / "points.csv");
    EXPECT_EQ(file.temp_path().filename().string(), ".points.csv.tmp-" + std::to_string(::getpid()));
    EXPECT_NE(file.temp_path().extension(), ".csv");
  }
  EXPECT_FALSE(fs::exists(dir / (".points.csv.tmp-" + std::to_string(::getpid()))));
  fs::remove_all(dir);
}

TEST(Printable, EscapesControlCharactersOnly) {
  EXPECT_EQ(printable("evil\x1b[31mRED\a"), "evil\\x1b[31mRED\\x07");
  EXPECT_EQ(printable("a\nb\tc\rd\x7f"), "a\\nb\\tc\\rd\\x7f");
  EXPECT_EQ(printable("line\n  | log", true), "line\n  | log");
  EXPECT_EQ(printable("\xc2\x9b"
                      "2J"),
            "\\u009b2J");                                                              // C1 CSI
  EXPECT_EQ(printable("Sainte-H\xc3\xa9l\xc3\xa8ne"), "Sainte-H\xc3\xa9l\xc3\xa8ne");  // UTF-8 kept
}

}  // namespace
}  // namespace wangscape
