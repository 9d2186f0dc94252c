#include "renders/external/movie.h"

#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/number_text.h"
#include "renders/external/child_process.h"

namespace wangscape {

namespace fs = std::filesystem;

bool write_frames_movie(const fs::path& dir, const std::string& pattern, double fps, const fs::path& movie) {
  const fs::path ffmpeg = find_program("ffmpeg");
  if (ffmpeg.empty()) return false;
  const fs::path log = dir / "ffmpeg.log";
  AtomicPath out(movie);
  // The temporary does not end in .mp4: the format is named (-f mp4).
  const ChildExit exit = run_logged(
      {ffmpeg.string(), "-y", "-loglevel", "error", "-framerate", number_text(fps), "-i", (dir / pattern).string(),
       "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", "mp4", out.temp_path().string()},
      log);
  if (!exit.exited || exit.status != 0) throw Error(movie, "", "ffmpeg " + exit.describe() + last_log_lines(log, 3));
  out.commit();
  std::error_code ec;
  fs::remove(log, ec);
  return true;
}

}  // namespace wangscape
