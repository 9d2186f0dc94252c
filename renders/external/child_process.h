// Running an external program (Blender, ...) with its output captured in a log file:
// PATH lookup with an environment override, fork/exec without a shell (no quoting issues).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace wangscape {

// `program` resolved through PATH (or checked as given when it contains a '/'); empty when
// not found or not executable.
std::filesystem::path find_program(const std::string& program);

struct ChildExit {
  bool exited = false;  // normal exit (else killed by a signal)
  int status = 0;       // exit status, or the signal number
  double seconds = 0;   // wall-clock time
  // "exited with status N" / "was killed by signal N".
  std::string describe() const;
};

// Runs argv[0] (a path) with argv, stdin from /dev/null, stdout and stderr appended to
// `log`, in `working_dir` (empty: the current one). Waits for it, calling `while_running`
// (if set) about five times a second, e.g. to report progress read from the log. Throws
// std::runtime_error only when the process cannot be started. With `output` set, stdout goes
// to that file instead (truncated), e.g. an image the child writes to stdout.
ChildExit run_logged(const std::vector<std::string>& argv, const std::filesystem::path& log,
                     const std::filesystem::path& working_dir = {}, const std::function<void()>& while_running = {},
                     const std::filesystem::path& output = {});

// The last `max_bytes` bytes of the file `path` (empty when it cannot be read).
std::string read_log_tail(const std::filesystem::path& path, std::size_t max_bytes);

// The last `count` non-empty lines of the text file `path` (at most its last 16 KiB; lines
// end with '\n' or '\r', as progress lines do), each prefixed with "\n  | ", for quoting a
// tool's error in a message.
std::string last_log_lines(const std::filesystem::path& path, int count);

// The frames a renderer wrote into `dir` as f<k>.png (k in any number of digits, at most nine),
// by k; other files are left out.
std::map<int, std::filesystem::path> numbered_frames(const std::filesystem::path& dir);

}  // namespace wangscape
