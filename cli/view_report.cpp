// The figures of `wangscape view` on stdout (cli/view_report.h).
#include "cli/view_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/number_text.h"

namespace wangscape::cli {

namespace {
// The tiles drawn per level: "12, 30, 4".
std::string levels_text(const ViewFrameStats& stats) {
  std::string levels;
  for (std::uint64_t n : stats.levels) levels += (levels.empty() ? "" : ", ") + std::to_string(n);
  return levels;
}

// How far the exact image's figure lies above the frame's: 0 when both are the same, infinities
// included (two images identical to the truth have an infinite PSNR each: no gap, not NaN).
double gap(double exact, double frame) { return exact == frame ? 0.0 : exact - frame; }

// A figure in JSON, which has no infinity: null stands for an infinite PSNR (identical images).
std::string json_figure(double value) { return std::isfinite(value) ? number_text(value) : "null"; }
}  // namespace

std::string view_stats_json(const ViewFrameStats& stats) {
  const double fps = stats.frame_ms > 0 ? 1000.0 / stats.frame_ms : 0;
  return "{\"frame_ms\": " + number_text(stats.frame_ms) + ", \"fps\": " + number_text(fps) +
         ", \"depth_pixels\": " + std::to_string(stats.depth_pixels) +
         ", \"tiles\": {\"drawn\": " + std::to_string(stats.tiles_drawn) +
         ", \"culled\": " + std::to_string(stats.tiles_culled) + ", \"steep\": " + std::to_string(stats.steep_tiles) +
         "}, \"levels\": [" + levels_text(stats) + "], \"ray_cast\": " + (stats.ray_cast ? "true" : "false") + "}";
}

std::string comparison_json_members(const ViewComparison& v, int frame_samples) {
  const ImageComparison& c = v.comparison;
  const ImageComparison& e = v.exact;
  return "\"psnr_db\": " + json_figure(c.psnr_db) + ", \"ssim\": " + number_text(c.ssim) +
         ", \"hole_share\": " + number_text(c.holes.share) + ", \"holes\": " + std::to_string(c.holes.holes) +
         ", \"reference_seconds\": " + number_text(v.reference.seconds) +
         ", \"truth_samples\": " + std::to_string(v.reference.samples_per_pixel) +
         ", \"exact_psnr_db\": " + json_figure(e.psnr_db) + ", \"exact_ssim\": " + number_text(e.ssim) +
         ", \"exact_hole_share\": " + number_text(e.holes.share) +
         ", \"psnr_gap_db\": " + json_figure(gap(e.psnr_db, c.psnr_db)) +
         ", \"ssim_gap\": " + number_text(gap(e.ssim, c.ssim)) +
         ", \"exact_seconds\": " + number_text(v.one_sample.seconds) +
         ", \"samples\": " + std::to_string(frame_samples);
}

void print_view_stats(const ViewFrameStats& stats, const Camera& camera, int width, int height, int frames, bool json) {
  if (json) {
    std::printf("%s\n", view_stats_json(stats).c_str());
    return;
  }
  std::printf("eye: %.2f %.2f %.2f (ENU m), looking at %.2f %.2f %.2f, fov %.1f degrees, %dx%d\n", camera.position[0],
              camera.position[1], camera.position[2], camera.target[0], camera.target[1], camera.target[2],
              camera.fov_degrees, width, height);
  std::printf("frame: %.2f ms (%.1f frames/s, median of %d)\n", stats.frame_ms,
              stats.frame_ms > 0 ? 1000 / stats.frame_ms : 0.0, frames);
  std::printf("of it: tiles %.2f ms, LDIs %.2f ms, terrain %.2f ms, near field %.2f ms, sky and resolve %.2f ms\n",
              stats.phase_ms[0], stats.phase_ms[1], stats.phase_ms[2], stats.phase_ms[3], stats.phase_ms[4]);
  if (stats.ray_cast) std::printf("drawn by: rays (the whole frame ray cast, --engine)\n");
  std::printf("near field: %llu tiles, %llu rays; %llu LDI tiles behind it not drawn\n",
              static_cast<unsigned long long>(stats.near_tiles), static_cast<unsigned long long>(stats.near_rays),
              static_cast<unsigned long long>(stats.tiles_occluded));
  std::printf("depth pixels: %llu (%.1f M/s)\n", static_cast<unsigned long long>(stats.depth_pixels),
              stats.frame_ms > 0 ? double(stats.depth_pixels) / stats.frame_ms / 1e3 : 0.0);
  std::printf("terrain: %llu triangles, %llu pixels tested\n", static_cast<unsigned long long>(stats.terrain_triangles),
              static_cast<unsigned long long>(stats.terrain_pixels));
  std::printf("tiles: %llu drawn (%llu from the steep sets, seen from above), %llu culled\n",
              static_cast<unsigned long long>(stats.tiles_drawn), static_cast<unsigned long long>(stats.steep_tiles),
              static_cast<unsigned long long>(stats.tiles_culled));
  std::printf("tiles per level (last: far field): %s\n", levels_text(stats).c_str());
}

void print_comparison(const ViewComparison& v, int frame_samples, const ViewFrameStats& frame,
                      const std::filesystem::path& truth_out, bool json) {
  const ImageComparison& c = v.comparison;
  const ImageComparison& e = v.exact;
  if (json) {
    std::printf("{%s, \"frame_ms\": %s}\n", comparison_json_members(v, frame_samples).c_str(),
                number_text(frame.frame_ms).c_str());
    return;
  }
  std::printf(
      "PSNR: %.2f dB (the exact geometry at %d sample(s) per pixel: %.2f dB, a gap of %.2f dB)\n"
      "SSIM: %.4f (exact: %.4f, a gap of %.4f)\n"
      "holes: %.4f %% of the pixels (%llu; %.4f %% of the truth's covered)\n"
      "truth: %d samples per pixel, %.2f s%s%s; exact image: %.2f s; the frame: %.1f ms\n",
      c.psnr_db, frame_samples, e.psnr_db, gap(e.psnr_db, c.psnr_db), c.ssim, e.ssim, gap(e.ssim, c.ssim),
      100 * c.holes.share, static_cast<unsigned long long>(c.holes.holes), 100 * c.holes.share_of_covered,
      v.reference.samples_per_pixel, v.reference.seconds, truth_out.empty() ? "" : ", saved to ",
      truth_out.string().c_str(), v.one_sample.seconds, frame.frame_ms);
}

void print_path_comparison(const PathFrame& frame) {
  std::printf("{\"frame\": %lld, \"frame_ms\": %s, %s}\n", frame.index, number_text(frame.frame_ms).c_str(),
              comparison_json_members(*frame.comparison, 1).c_str());
  std::fflush(stdout);
}

void print_path_stats(std::vector<double> frame_ms, double fresh_share, int width, int height, double fps, bool json) {
  std::sort(frame_ms.begin(), frame_ms.end());
  const auto at = [&](double q) {
    return frame_ms[std::min(frame_ms.size() - 1, std::size_t(q * double(frame_ms.size())))];
  };
  const auto frames = static_cast<long long>(frame_ms.size());
  if (json)
    std::printf(
        "{\"frame_ms\": %s, \"frame_ms_p95\": %s, \"frame_ms_max\": %s, \"fresh_share\": %s, \"frames\": %lld}\n",
        number_text(at(0.5)).c_str(), number_text(at(0.95)).c_str(), number_text(frame_ms.back()).c_str(),
        number_text(fresh_share).c_str(), frames);
  else
    std::printf(
        "%lld frames of %dx%d at %s frames/s: median %.2f ms, 95th percentile %.2f ms, max %.2f ms; "
        "traced anew: %.1f %% of the pixels a frame\n",
        frames, width, height, number_text(fps).c_str(), at(0.5), at(0.95), frame_ms.back(), 100 * fresh_share);
}

}  // namespace wangscape::cli
