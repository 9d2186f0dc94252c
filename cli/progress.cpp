#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace wangscape::cli {

namespace {
std::int64_t now_ms() {
  using namespace std::chrono;
  return duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Progress::Progress(std::string label, std::uint64_t total, bool quiet)
    : label_(std::move(label)), total_(std::max<std::uint64_t>(total, 1)), enabled_(!quiet && isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::update(std::uint64_t done, const std::string& note) {
  if (!enabled_ || finished_) return;
  if (!note.empty()) last_note_ = note;
  const std::int64_t t = now_ms();
  if (done < total_ && last_draw_ms_ >= 0 && t - last_draw_ms_ < 50) return;
  last_draw_ms_ = t;
  last_drawn_ = done;
  constexpr int kWidth = 30;
  const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
  const int filled = static_cast<int>(fraction * kWidth);
  // "\x1b[K" clears what a longer note drew before.
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%%s%s\x1b[K", label_.c_str(), filled, "##############################",
               kWidth - filled, "", static_cast<int>(fraction * 100.0), last_note_.empty() ? "" : "  ",
               last_note_.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  if (last_drawn_ < total_) update(total_, last_note_);
  finished_ = true;
  std::fputc('\n', stderr);
}

}  // namespace wangscape::cli
