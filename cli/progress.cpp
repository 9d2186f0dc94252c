#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "core/number_text.h"
#include "core/printable.h"

namespace wangscape::cli {

namespace {
std::int64_t now_ms() {
  using namespace std::chrono;
  return duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count();
}

// "  12 s left", "  4 min 05 s left", "  2 h 10 min left" at the rate so far; empty until a
// second has passed and 1 % is done, and once all is.
std::string time_left_text(double elapsed_seconds, double fraction) {
  if (elapsed_seconds < 1 || fraction < 0.01 || fraction >= 1) return {};
  const auto left = static_cast<long long>(std::ceil(elapsed_seconds * (1 - fraction) / fraction));
  char text[48];
  if (left < 60)
    std::snprintf(text, sizeof text, "  %lld s left", left);
  else if (left < 3600)
    std::snprintf(text, sizeof text, "  %lld min %02lld s left", left / 60, left % 60);
  else
    std::snprintf(text, sizeof text, "  %lld h %02lld min left", left / 3600, left / 60 % 60);
  return text;
}
}  // namespace

Progress::Progress(std::string label, std::uint64_t total, bool quiet, bool time_left)
    : label_(std::move(label)),
      total_(std::max<std::uint64_t>(total, 1)),
      enabled_(!quiet && isatty(STDERR_FILENO)),
      time_left_(time_left),
      start_ms_(now_ms()) {}

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
  const std::string left = time_left_ ? time_left_text(double(t - start_ms_) / 1000, fraction) : std::string();
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%%s%s%s\x1b[K", label_.c_str(), filled, "##############################",
               kWidth - filled, "", static_cast<int>(fraction * 100.0), left.c_str(), last_note_.empty() ? "" : "  ",
               last_note_.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  if (last_drawn_ < total_) update(total_, last_note_);
  finished_ = true;
  std::fputc('\n', stderr);
}

namespace {
// A file's size, or the sum of the regular files under a folder; 0 when it cannot be read.
double bytes_at(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_regular_file(path, error)) {
    const auto size = fs::file_size(path, error);
    return error ? 0.0 : double(size);
  }
  double total = 0;
  for (fs::recursive_directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
    std::error_code size_error;
    if (it->is_regular_file(size_error)) {
      const auto size = it->file_size(size_error);
      if (!size_error) total += double(size);
    }
  }
  return total;
}
}  // namespace

std::string shown_path(const std::filesystem::path& path) {
  std::error_code error;
  if (path.is_absolute()) {
    const auto here = std::filesystem::current_path(error);
    const auto inside = error ? std::filesystem::path() : path.lexically_relative(here);
    if (!inside.empty() && *inside.begin() != "..") return printable(inside.string());
  }
  return printable(path.string());
}

std::string duration_text(double seconds) {
  if (seconds < 10) return fixed_text(seconds, 2) + " s";
  if (seconds < 60) return fixed_text(seconds, 1) + " s";
  const auto whole = static_cast<long long>(std::lround(seconds));
  return std::to_string(whole / 60) + " min " + std::to_string(whole % 60) + " s";
}

double WriteReport::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void WriteReport::wrote(const std::filesystem::path& path, const std::string& details) const {
  wrote(std::vector<std::filesystem::path>{path}, details);
}

void WriteReport::wrote(const std::vector<std::filesystem::path>& paths, const std::string& details) const {
  if (quiet_ || paths.empty()) return;
  std::string names;
  double bytes = 0;
  for (const auto& path : paths) {
    if (!names.empty()) names += ", ";
    names += shown_path(path);
    bytes += bytes_at(path);
  }
  std::string what = details;
  if (!what.empty()) what += ", ";
  what += byte_text(bytes);
  std::fprintf(stderr, "wangscape: wrote %s (%s) in %s\n", names.c_str(), what.c_str(),
               duration_text(seconds()).c_str());
}

}  // namespace wangscape::cli
