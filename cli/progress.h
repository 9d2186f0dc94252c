// A progress bar on stderr for long work, shown only when stderr is a terminal and the
// user did not ask for --quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wangscape::cli {

class Progress {
 public:
  // With `time_left`, the bar says how long the rest will take at the rate so far (from a
  // second in and 1 % done); a caller whose work is uneven (frames already there) says it itself.
  Progress(std::string label, std::uint64_t total, bool quiet, bool time_left = true);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Sets the amount of work done so far (0..total); redraws at most ~20 times a second. `note`
  // is drawn after the bar (e.g. "12 / 448 LDIs, 3.1 M rays/s").
  void update(std::uint64_t done, const std::string& note = {});
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  bool time_left_;
  std::int64_t start_ms_;
  bool finished_ = false;
  std::int64_t last_draw_ms_ = -1;
  std::uint64_t last_drawn_ = 0;
  std::string last_note_;
};

// The one line a command says when it has written something, on stderr, silent under --quiet
// (terminal or not): "wangscape: wrote PATH (DETAILS, SIZE) in TIME", or "PATH, PATH2 (...)" for
// a command that writes several. SIZE is the files' size (a folder: the sum of its files); TIME
// runs from the report's construction (the command's start).
class WriteReport {
 public:
  explicit WriteReport(bool quiet) : quiet_(quiet), start_(std::chrono::steady_clock::now()) {}
  // DETAILS: counts, e.g. "4410 instances from 230 tiles"; may be empty.
  void wrote(const std::filesystem::path& path, const std::string& details) const;
  void wrote(const std::vector<std::filesystem::path>& paths, const std::string& details) const;
  double seconds() const;

 private:
  bool quiet_;
  std::chrono::steady_clock::time_point start_;
};

// A path for a message: an absolute one inside the current folder as relative to it
// ("small/render.png"), any other as it is; control characters escaped.
std::string shown_path(const std::filesystem::path& path);

// "0.42 s", "12.3 s", "1 min 42 s".
std::string duration_text(double seconds);

}  // namespace wangscape::cli
