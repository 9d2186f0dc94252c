// `wangscape view`'s request: its checks and its camera (cli/view_request.h).
#include "cli/view_request.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/number_text.h"
#include "core/vecmath.h"
#include "scene/scene_file.h"

namespace wangscape::cli {

namespace {

// A flag that needs another: "--diff: needs --compare".
void require(bool needed, bool given, const char* flag, const char* needs) {
  if (needed && !given) throw Error(std::string(flag) + ": needs " + needs);
}

// "--FLAG VALUE: expected LOW .. HIGH UNIT" unless LOW <= value <= HIGH (NaN fails).
template <class T>
void check_range(T value, T low, T high, const char* flag, const std::string& unit) {
  if (!(value >= low && value <= high))
    throw Error(std::string(flag) + " " + number_text(value) + ": expected " + number_text(low) + " .. " +
                number_text(high) + " " + unit);
}

// "--FLAG E,N,H: expected each of E, N, H within -1e+07 .. 1e+07 meters" unless each part is, as
// the scene file's camera (NaN fails; a NaN height is --camera's height not given).
void check_position(const std::optional<std::array<double, 3>>& position, const char* flag) {
  if (!position) return;
  const auto& p = *position;
  const bool no_height = std::isnan(p[2]);
  const auto in_range = [](double v) { return std::abs(v) <= kMaxCameraMeters; };
  if (in_range(p[0]) && in_range(p[1]) && (no_height || in_range(p[2]))) return;
  std::string given = number_text(p[0]) + "," + number_text(p[1]);
  if (!no_height) given += "," + number_text(p[2]);
  throw Error(std::string(flag) + " " + given + ": expected each of E, N, H within " + number_text(-kMaxCameraMeters) +
              " .. " + number_text(kMaxCameraMeters) + " meters of the scene's origin");
}

}  // namespace

void check_view_request(const ViewRequest& request) {
  if ((request.width != 0 || request.height != 0) &&
      (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384))
    throw Error("--size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                ": expected WIDTHxHEIGHT, each 1 .. 16384 pixels");
  check_position(request.camera, "--camera");
  check_position(request.look_at, "--look-at");
  if (request.fov_degrees) check_field_of_view(*request.fov_degrees, "--fov");
  if (!request.path.empty() && request.frames_dir.empty() && !request.stats && request.compare_every == 0)
    throw Error("--path: needs --frames OUTDIR (or --stats, or --compare-every K)");
  if (request.compare_every < 0) throw Error("--compare-every: expected a number of frames, 1 or more");
  require(request.compare_every > 0, !request.path.empty(), "--compare-every", "--path FILE");
  if (request.fps) check_range(*request.fps, kMinViewFps, kMaxViewFps, "--fps", "frames per second");
  if (request.repeat < 0 || request.repeat > 100000) throw Error("--repeat: expected 0 .. 100000 frames");
  check_range(request.settings.detail, kMinViewDetail, kMaxViewDetail, "--detail",
              "(1: the pack's levels at their own distances)");
  require(!request.diff.empty(), request.compare, "--diff", "--compare");
  check_range(request.settings.near_field, 0.0, kMaxNearField, "--near", "meters (0: LDIs everywhere)");
  check_range(request.settings.samples, 1, kMaxViewSamples, "--spp", "samples per pixel");
  check_range(request.truth_samples, 1, kMaxReferenceSamples, "--truth-spp", "samples per pixel");
  require(!request.truth_out.empty(), request.compare, "--reference", "--compare");
  require(!request.side_by_side.empty(), request.compare, "--side-by-side", "--compare");
}

void check_view_memory(const ViewRequest& request, int width, int height, bool window) {
  // Bytes a pixel, as measured (peak resident memory at 1024 x 1024 and 2048 x 2048 pixels, the
  // small template's folder, issue 41): the image (3) and the z-buffer (8), and a z-buffer of
  // each thread for the LDIs' splats (8 each); the sums of --spp N (12); the sample cache of a
  // path or the window (64: two 24-byte samples, the key, need, fresh and lattice bytes); the
  // truth, the exact image, their masks and SSIM's planes of --compare (about 120).
  const auto threads =
      double(std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  const bool cached = window || (!request.path.empty() && request.cached);
  const bool compares = request.compare || request.compare_every > 0;
  const double per_pixel =
      11 + 8 * threads + (request.settings.samples > 1 ? 12 : 0) + (cached ? 64 : 0) + (compares ? 120 : 0);
  const double pixels = double(width) * double(height);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string what =
      (request.width ? "--size " + size : "the scene's image size " + size + " ([image] width, height)") +
      ": frames of " + fixed_text(pixels, 0) + " pixels at about " + fixed_text(per_pixel, 0) + " bytes a pixel (" +
      fixed_text(threads, 0) + " threads" + (cached ? ", the sample cache" : "") +
      (compares ? ", the comparison" : "") + ")";
  if (const auto excess = memory_estimate_excess(what, pixels * per_pixel))
    throw Error(*excess + "; lower --size" + (threads > 1 ? " or --threads" : ""));
}

bool wants_window(const ViewRequest& request) {
  return request.out.empty() && request.path.empty() && !request.stats && !request.compare;
}

Camera request_camera(const ViewWorld& world, const ViewRequest& request) {
  // The library's refusals, checked first with the flags' names.
  const Camera& scene = world.scene().camera;
  check_field_of_view(request.fov_degrees.value_or(scene.fov_degrees), "--fov");
  if (request.camera && std::isnan((*request.camera)[2]) &&
      !world.scene().field->ground.height((*request.camera)[0], (*request.camera)[1]))
    throw Error("--camera " + number_text((*request.camera)[0]) + "," + number_text((*request.camera)[1]) +
                ": not over the ground; give the height too (E,N,H)");
  if (!looks_sideways(request.camera.value_or(scene.position), request.look_at.value_or(scene.target)))
    throw Error("--look-at: must lie sideways of the camera (not straight above, below or at it)");
  return view_camera(world, {request.camera, request.look_at, request.fov_degrees});
}

}  // namespace wangscape::cli
