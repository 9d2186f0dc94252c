// A folder of numbered PNG frames into an .mp4 through ffmpeg, when ffmpeg is on PATH: what
// `wangscape view --path` and `wangscape render --path` end with.
#pragma once

#include <filesystem>
#include <string>

namespace wangscape {

// Encodes `dir`/`pattern` (a printf pattern of the frames' numbers from 0, e.g. "frame-%05d.png")
// at `fps` frames a second into `movie` (H.264, yuv420p, odd sizes padded to even), written
// atomically; ffmpeg's messages go to DIR/ffmpeg.log, removed when it succeeds. Returns false,
// writing nothing, when ffmpeg is not on PATH; throws Error naming the movie, with the log's last
// lines, when ffmpeg fails.
bool write_frames_movie(const std::filesystem::path& dir, const std::string& pattern, double fps,
                        const std::filesystem::path& movie);

}  // namespace wangscape
