// The figures `wangscape view` prints on stdout (docs/viewer.md): a camera's frame statistics,
// a frame against the truth, and a path's frame times and compared frames; text, or JSON with
// exactly the documented keys (tests/cli/view_*_check.py read them).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "renders/view/view_frames.h"

namespace wangscape::cli {

// {"frame_ms": ..., "fps": ..., "depth_pixels": ..., "tiles": {...}, "levels": [...], "ray_cast": ...}
std::string view_stats_json(const ViewFrameStats& stats);
// The comparison's figures as one JSON object's members (no braces): "psnr_db": ..., ...
std::string comparison_json_members(const ViewComparison& v, int frame_samples);

// --stats: the median statistics of `frames` frames of `camera` at width x height.
void print_view_stats(const ViewFrameStats& stats, const Camera& camera, int width, int height, int frames, bool json);
// --compare: the frame (drawn at `frame_samples` samples per pixel, in `frame.frame_ms`) against
// the truth; `truth_out` where the truth was saved (empty: nowhere).
void print_comparison(const ViewComparison& v, int frame_samples, const ViewFrameStats& frame,
                      const std::filesystem::path& truth_out, bool json);
// --path --compare-every: one JSON line for a compared frame.
void print_path_comparison(const PathFrame& frame);
// --path --stats: the frames' times (ms) at width x height and `fps`, and the mean share of the
// pixels traced anew.
void print_path_stats(std::vector<double> frame_ms, double fresh_share, int width, int height, double fps, bool json);

}  // namespace wangscape::cli
