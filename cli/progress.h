// A progress bar on stderr for long work, shown only when stderr is a terminal and the
// user did not ask for --quiet.
#pragma once

#include <cstdint>
#include <string>

namespace wangscape::cli {

class Progress {
 public:
  Progress(std::string label, std::uint64_t total, bool quiet);
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
  bool finished_ = false;
  std::int64_t last_draw_ms_ = -1;
  std::uint64_t last_drawn_ = 0;
  std::string last_note_;
};

}  // namespace wangscape::cli
