#include "folder/ldi_pack.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <type_traits>
#include <utility>

#include "core/atomic_file.h"
#include "core/number_text.h"
#include "core/vecmath.h"

namespace wangscape {

static_assert(std::endian::native == std::endian::little, "the pack is little endian and read in place");

namespace {

// The fixed header at offset 0 (64 bytes).
struct PackHeader {
  char magic[8];
  std::uint32_t version, header_bytes;
  std::uint32_t tiles, levels, directions, image_width;
  float tile_size, head_height, prism_top, fov_degrees;
  std::uint64_t file_bytes;    // the whole file: a shorter file was truncated
  std::uint64_t index_offset;  // the index: (tile, level, direction) -> IndexEntry
};
static_assert(sizeof(PackHeader) == 64);

// The header's fields that are LdiPackInfo's, each with its place in LdiPackInfo: one list for the
// writer and the reader. field(in_header, in_info) for each.
template <class Header, class Info, class Field>
void for_each_info_field(Header& h, Info& info, const Field& field) {
  field(h.tiles, info.tiles);
  field(h.levels, info.levels);
  field(h.directions, info.directions);
  field(h.image_width, info.image_width);
  field(h.tile_size, info.tile_size);
  field(h.head_height, info.head_height);
  field(h.prism_top, info.prism_top);
  field(h.fov_degrees, info.fov_degrees);
}

// The arrays right after the header, in file order (4 bytes an entry, arrays_bytes):
// array(values, count) for each.
template <class Info, class Array>
void for_each_info_array(Info& info, const Array& array) {
  array(info.resolutions, info.levels);
  array(info.level_distances, info.levels);
  array(info.elevations, info.levels);
  array(info.azimuths, info.directions);
}

struct IndexEntry {
  std::uint64_t offset, bytes;
};
static_assert(sizeof(IndexEntry) == 16);

// Sanity bounds, so that a corrupt header cannot ask for absurd allocations.
constexpr std::uint32_t kMaxTiles = 65536, kMaxLevels = 64, kMaxDirections = 64;

constexpr std::uint64_t align8(std::uint64_t x) { return (x + 7) & ~std::uint64_t{7}; }

// Per-level and per-direction arrays right after the header.
std::uint64_t arrays_bytes(std::uint64_t levels, std::uint64_t directions) {
  return levels * 4 * 3 + directions * 4;  // resolutions, distances, elevations; azimuths
}

// Version 3: the light record right after the arrays, as it is in memory (4-byte fields, no padding).
static_assert(sizeof(LdiPackLight) == 72 && std::is_trivially_copyable_v<LdiPackLight>);
std::uint64_t light_bytes(const LdiPackInfo& info) { return info.light ? sizeof(LdiPackLight) : 0; }

// Where the sections of an LDI block sit, from its frame.
struct BlockLayout {
  std::uint64_t row_spans, spans, counts, depth_pixels, total;
  explicit BlockLayout(const LdiFrame& f) {
    row_spans = sizeof(LdiFrame);
    spans = align8(row_spans + (std::uint64_t{f.height} + 1) * 4);
    counts = align8(spans + std::uint64_t{f.span_count} * sizeof(LdiSpan));
    depth_pixels = align8(counts + f.pixel_count);
    total = depth_pixels + std::uint64_t{f.depth_pixel_count} * sizeof(DepthPixel);
  }
};

std::size_t entry_index(const LdiPackInfo& info, std::uint32_t tile, std::uint32_t level, std::uint32_t direction) {
  return (std::size_t{tile} * info.levels + level) * info.directions + direction;
}

}  // namespace

// ---- views ----------------------------------------------------------------------------------

std::span<const DepthPixel> LdiView::pixel(int x, int y) const {
  if (x < 0 || y < 0 || std::uint32_t(x) >= frame->width || std::uint32_t(y) >= frame->height) return {};
  const auto first = spans.begin() + row_spans[std::size_t(y)], last = spans.begin() + row_spans[std::size_t(y) + 1];
  // The last span starting at or before x.
  auto it = std::upper_bound(first, last, x, [](int v, const LdiSpan& s) { return v < int(s.x); });
  if (it == first) return {};
  --it;
  if (x >= int(it->x) + int(it->length)) return {};
  std::uint32_t depth = it->first_depth;
  for (int k = it->x; k < x; ++k) depth += counts[it->first_pixel + std::uint32_t(k - it->x)];
  return depth_pixels.subspan(depth, counts[it->first_pixel + std::uint32_t(x - it->x)]);
}

std::array<float, 3> LdiView::position(int x, int y, const DepthPixel& p) const {
  const LdiFrame& f = *frame;
  const float a = (float(x) + 0.5f) * f.pixel_size, b = (float(y) + 0.5f) * f.pixel_size, d = depth_meters(p);
  std::array<float, 3> out{};
  for (int c = 0; c < 3; ++c) out[c] = f.origin[c] + a * f.right[c] - b * f.up[c] + d * f.forward[c];
  return out;
}

std::uint16_t encode_octahedral(const std::array<float, 3>& n) {
  const float l1 = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
  float u = n[0] / l1, v = n[1] / l1;
  if (n[2] < 0) {
    const float fu = (1.0f - std::abs(v)) * std::copysign(1.0f, u), fv = (1.0f - std::abs(u)) * std::copysign(1.0f, v);
    u = fu;
    v = fv;
  }
  auto q = [](float c) { return std::uint16_t(std::lround((std::clamp(c, -1.0f, 1.0f) * 0.5f + 0.5f) * 255.0f)); };
  return std::uint16_t(q(u) | (q(v) << 8));
}

std::array<float, 3> decode_octahedral(std::uint16_t code) {
  float u = float(code & 0xff) / 255.0f * 2.0f - 1.0f, v = float(code >> 8) / 255.0f * 2.0f - 1.0f;
  const float z = 1.0f - std::abs(u) - std::abs(v);
  if (z < 0) {
    const float fu = (1.0f - std::abs(v)) * std::copysign(1.0f, u), fv = (1.0f - std::abs(u)) * std::copysign(1.0f, v);
    u = fu;
    v = fv;
  }
  const float len = std::sqrt(u * u + v * v + z * z);
  return {u / len, v / len, z / len};
}

// ---- writing --------------------------------------------------------------------------------

namespace {

template <class T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
void put_all(std::ostream& out, std::span<const T> values) {
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size_bytes()));
}
// Writes zeros from `at` up to `target` (alignment padding, and the room the header and index
// take until commit() writes them).
void pad_to(std::ostream& out, std::uint64_t& at, std::uint64_t target) {
  static constexpr char zeros[64] = {};
  while (at < target) {
    const std::uint64_t n = std::min<std::uint64_t>(sizeof(zeros), target - at);
    out.write(zeros, static_cast<std::streamsize>(n));
    at += n;
  }
}

std::uint64_t index_offset_of(const LdiPackInfo& info) {
  return align8(sizeof(PackHeader) + arrays_bytes(info.levels, info.directions) + light_bytes(info));
}

}  // namespace

LdiPackWriter::LdiPackWriter(std::filesystem::path path, LdiPackInfo info)
    : path_(std::move(path)), info_(std::move(info)) {
  if (info_.tiles == 0 || info_.levels == 0 || info_.directions == 0 || info_.tiles > kMaxTiles ||
      info_.levels > kMaxLevels || info_.directions > kMaxDirections || info_.resolutions.size() != info_.levels ||
      info_.level_distances.size() != info_.levels || info_.elevations.size() != info_.levels ||
      info_.azimuths.size() != info_.directions)
    throw Error(path_, "",
                "cannot write a pack of " + std::to_string(info_.tiles) + " tiles x " + std::to_string(info_.levels) +
                    " levels x " + std::to_string(info_.directions) +
                    " directions (or with per-level arrays of the wrong length)");
  file_ = std::make_unique<AtomicFile>(path_);
  const std::size_t n = std::size_t{info_.tiles} * info_.levels * info_.directions;
  offsets_.assign(n, 0);
  sizes_.assign(n, 0);
  // Header, arrays and index are rewritten by commit(); reserve their room now.
  end_ = index_offset_of(info_) + n * sizeof(IndexEntry);
  std::uint64_t at = 0;
  pad_to(file_->stream(), at, end_);
}

LdiPackWriter::~LdiPackWriter() = default;

void LdiPackWriter::add(const LdiImage& ldi) {
  LdiFrame frame = ldi.frame;
  frame.span_count = std::uint32_t(ldi.spans.size());
  frame.pixel_count = std::uint32_t(ldi.counts.size());
  frame.depth_pixel_count = std::uint32_t(ldi.depth_pixels.size());
  if (frame.tile >= info_.tiles || frame.level >= info_.levels || frame.direction >= info_.directions ||
      ldi.row_spans.size() != std::size_t{frame.height} + 1)
    throw Error(path_, "",
                "LDI (tile " + std::to_string(frame.tile) + ", level " + std::to_string(frame.level) + ", direction " +
                    std::to_string(frame.direction) + ") does not fit the pack");
  const std::size_t e = entry_index(info_, frame.tile, frame.level, frame.direction);
  if (sizes_[e] != 0) throw Error(path_, "", "an LDI was added twice");
  const BlockLayout layout(frame);
  std::ostream& out = file_->stream();
  offsets_[e] = end_;
  std::uint64_t at = 0;  // relative to the block
  put(out, frame);
  at += sizeof(LdiFrame);
  put_all(out, std::span<const std::uint32_t>(ldi.row_spans));
  at += ldi.row_spans.size() * 4;
  pad_to(out, at, layout.spans);
  put_all(out, std::span<const LdiSpan>(ldi.spans));
  at += ldi.spans.size() * sizeof(LdiSpan);
  pad_to(out, at, layout.counts);
  put_all(out, std::span<const std::uint8_t>(ldi.counts));
  at += ldi.counts.size();
  pad_to(out, at, layout.depth_pixels);
  put_all(out, std::span<const DepthPixel>(ldi.depth_pixels));
  at += ldi.depth_pixels.size() * sizeof(DepthPixel);
  pad_to(out, at, align8(layout.total));  // the next block starts on 8 bytes too
  sizes_[e] = layout.total;
  end_ += at;
}

void LdiPackWriter::commit() {
  for (std::uint64_t s : sizes_)
    if (s == 0) throw Error(path_, "", "not every (tile, level, direction) LDI was added");
  PackHeader h{};
  std::memcpy(h.magic, kLdiPackMagic, sizeof(h.magic));
  h.version = info_.light ? kLdiPackVersion : kLdiPackOldestVersion;  // (version 2 has no light)
  h.header_bytes = sizeof(PackHeader);
  for_each_info_field(h, info_, [](auto& in_header, const auto& in_info) { in_header = in_info; });
  h.file_bytes = end_;
  h.index_offset = index_offset_of(info_);
  std::ostream& out = file_->stream();
  out.seekp(0);
  put(out, h);
  for_each_info_array(info_, [&](const auto& values, std::uint32_t) { put_all(out, std::span(values)); });
  if (info_.light) put(out, *info_.light);
  std::uint64_t at = sizeof(PackHeader) + arrays_bytes(info_.levels, info_.directions) + light_bytes(info_);
  pad_to(out, at, h.index_offset);
  for (std::size_t e = 0; e < sizes_.size(); ++e) put(out, IndexEntry{offsets_[e], sizes_[e]});
  file_->commit();
}

void write_ldi_pack(const std::filesystem::path& path, const LdiPackInfo& info, std::span<const LdiImage> ldis) {
  LdiPackWriter writer(path, info);
  for (const LdiImage& ldi : ldis) writer.add(ldi);
  writer.commit();
}

// ---- reading --------------------------------------------------------------------------------

namespace {

// A frame's geometry against the pack's header: what the builder writes (make_frame in
// ldi_build.cpp), within float rounding. Checked for finiteness only, a frame with a zero right
// axis, a pixel of 1e30 m, an origin 1e30 m away or 65,535 pixels at a level of 429 passed, and
// the view drew from it (issue 41).
constexpr double kFrameTolerance = 1e-3;  // float rounding is about 1e-7

Vector3d wide(const std::array<float, 3>& v) { return Vector3d{v[0], v[1], v[2]}; }

std::string vector_text(const Vector3d& v) {
  std::string out(1, '(');  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "(" + ...
  for (std::size_t c = 0; c < 3; ++c) {
    out += number_text(float(v[c]));
    out += c < 2 ? ", " : ")";
  }
  return out;
}

// Unit axes at right angles (up = right x forward), the rays along the pack's azimuth of the
// frame's direction and elevation of its level.
template <class Fail>
void check_frame_axes(const LdiFrame& f, const LdiPackInfo& info, Fail&& fail) {
  const Vector3d right = wide(f.right), up = wide(f.up), forward = wide(f.forward);
  for (const auto& [name, axis] : {std::pair{"right", right}, std::pair{"up", up}, std::pair{"forward", forward}})
    if (!(std::abs(length(axis) - 1) <= kFrameTolerance))
      fail(std::string("its frame's ") + name + " axis " + vector_text(axis) + " has length " +
           number_text(length(axis)) + "; expected a unit vector");
  if (!(std::abs(dot(right, up)) <= kFrameTolerance && std::abs(dot(right, forward)) <= kFrameTolerance &&
        std::abs(dot(up, forward)) <= kFrameTolerance && dot(cross(right, forward), up) > 0))
    fail("its frame's axes right " + vector_text(right) + ", up " + vector_text(up) + ", forward " +
         vector_text(forward) + " are not at right angles with up = right x forward");
  const float azimuth = info.azimuths[f.direction], elevation = info.elevations[f.level];
  const double a = double(azimuth) * std::numbers::pi / 180, e = double(elevation) * std::numbers::pi / 180;
  const Vector3d along{std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), -std::sin(e)};
  if (!(length(forward - along) <= kFrameTolerance && std::abs(f.azimuth_degrees - azimuth) <= kFrameTolerance &&
        std::abs(f.elevation_degrees - elevation) <= kFrameTolerance))
    fail("its frame looks along azimuth " + number_text(f.azimuth_degrees) + ", elevation " +
         number_text(f.elevation_degrees) + " (forward " + vector_text(forward) +
         "); its direction and level are azimuth " + number_text(azimuth) + ", elevation " + number_text(elevation) +
         " degrees");
}

// The level's pixel size; an image and a depth that cover the tile's prism, no more: no side
// and no depth beyond the prism's diagonal, the origin (the image's corner) within it of the
// prism's centre.
template <class Fail>
void check_frame_extent(const LdiFrame& f, const LdiPackInfo& info, Fail&& fail) {
  const double tile = info.tile_size, pixel = tile / info.resolutions[f.level];
  if (!(std::abs(f.pixel_size / pixel - 1) <= kFrameTolerance))
    fail("its pixel size " + number_text(f.pixel_size) + " m is not the level's " + number_text(float(pixel)) + " m (" +
         number_text(info.tile_size) + " m / " + std::to_string(info.resolutions[f.level]) + " pixels)");
  const double height = double(info.prism_top) - kLdiPrismBottom;
  const double diagonal = std::sqrt(2 * tile * tile + height * height);
  const double most_pixels = std::floor(diagonal / pixel * (1 + kFrameTolerance)) + 2;
  if (f.width > most_pixels || f.height > most_pixels)
    fail("its size " + std::to_string(f.width) + " x " + std::to_string(f.height) + " pixels is more than the tile's " +
         "prism spans at " + std::to_string(info.resolutions[f.level]) + " pixels a tile side (at most " +
         fixed_text(most_pixels, 0) + " a side)");
  if (!(f.depth_range <= diagonal * (1 + kFrameTolerance)))
    fail("its depth range " + number_text(f.depth_range) + " m is more than the tile's prism spans (" +
         fixed_text(diagonal, 3) + " m)");
  const Vector3d centre{tile / 2, tile / 2, (double(info.prism_top) + kLdiPrismBottom) / 2};
  const double away = length(wide(f.origin) - centre), most_away = diagonal + 2 * pixel;
  if (!(away <= most_away))
    fail("its origin " + vector_text(wide(f.origin)) + " lies " + significant_text(away, 6) +
         " m from the centre of the tile's prism; expected within " + fixed_text(most_away, 3) + " m");
}

// Checks of one block, in the order a reader needs them; `fail` throws.
template <class Fail>
LdiView validate_block(const std::uint8_t* block, std::uint64_t bytes, std::uint32_t tile, std::uint32_t level,
                       std::uint32_t direction, const LdiPackInfo& info, Fail&& fail) {
  if (bytes < sizeof(LdiFrame)) fail("its block is " + std::to_string(bytes) + " bytes, shorter than its frame");
  const auto* f = reinterpret_cast<const LdiFrame*>(block);
  if (f->tile != tile || f->level != level || f->direction != direction)
    fail("its frame says tile " + std::to_string(f->tile) + ", level " + std::to_string(f->level) + ", direction " +
         std::to_string(f->direction));
  if (f->width == 0 || f->height == 0 || f->width > 65535 || f->height > 65535)
    fail("its size " + std::to_string(f->width) + " x " + std::to_string(f->height) + " is out of range");
  if (std::uint64_t{f->pixel_count} > std::uint64_t{f->width} * f->height)
    fail("it claims more non-empty pixels than it has pixels");
  if (!(std::isfinite(f->pixel_size) && f->pixel_size > 0 && std::isfinite(f->depth_range) && f->depth_range > 0))
    fail("its pixel size or depth range is not a positive number");
  for (const auto* v : {&f->origin, &f->right, &f->up, &f->forward})
    for (float c : *v)
      if (!std::isfinite(c)) fail("its frame's origin or axes hold a number that is not finite");
  if (!std::isfinite(f->azimuth_degrees) || !(f->elevation_degrees >= -90 && f->elevation_degrees <= 90))
    fail("its frame's azimuth is not finite or its elevation is not in [-90, 90] degrees");
  check_frame_axes(*f, info, fail);
  check_frame_extent(*f, info, fail);
  const BlockLayout layout(*f);
  if (layout.total > bytes)
    fail("its sections need " + std::to_string(layout.total) + " bytes, its block has " + std::to_string(bytes));
  LdiView v;
  v.frame = f;
  v.row_spans = {reinterpret_cast<const std::uint32_t*>(block + layout.row_spans), std::size_t{f->height} + 1};
  v.spans = {reinterpret_cast<const LdiSpan*>(block + layout.spans), f->span_count};
  v.counts = {block + layout.counts, f->pixel_count};
  v.depth_pixels = {reinterpret_cast<const DepthPixel*>(block + layout.depth_pixels), f->depth_pixel_count};
  if (v.row_spans.front() != 0 || v.row_spans.back() != f->span_count) fail("its row table does not cover its spans");
  std::uint64_t pixel = 0, depth = 0;
  for (std::uint32_t y = 0; y < f->height; ++y) {
    if (v.row_spans[y + 1] < v.row_spans[y]) fail("its row table goes backwards at row " + std::to_string(y));
    std::uint32_t row_end = 0;
    for (std::uint32_t s = v.row_spans[y]; s < v.row_spans[y + 1]; ++s) {
      const LdiSpan& span = v.spans[s];
      if (span.length == 0 || span.x < row_end || std::uint32_t{span.x} + span.length > f->width)
        fail("span " + std::to_string(s) + " of row " + std::to_string(y) + " is out of its row or overlaps");
      if (span.first_pixel != pixel || span.first_depth != depth)
        fail("span " + std::to_string(s) + " points at pixel " + std::to_string(span.first_pixel) + " / depth pixel " +
             std::to_string(span.first_depth) + " instead of " + std::to_string(pixel) + " / " + std::to_string(depth));
      if (pixel + span.length > f->pixel_count) fail("its spans hold more pixels than its count table");
      for (std::uint32_t k = 0; k < span.length; ++k) {
        depth += v.counts[pixel + k];
      }
      pixel += span.length;
      row_end = std::uint32_t{span.x} + span.length;
    }
  }
  if (pixel != f->pixel_count || depth != f->depth_pixel_count)
    fail("its spans cover " + std::to_string(pixel) + " pixels and " + std::to_string(depth) +
         " depth pixels, its frame says " + std::to_string(f->pixel_count) + " and " +
         std::to_string(f->depth_pixel_count));
  return v;
}

// The light record: finite colours, a unit sun direction, counts and distances a build writes.
template <class Fail>
void check_light_numbers(const LdiPackLight& light, Fail&& fail) {
  const auto finite_at_least = [](float v, float lo) { return std::isfinite(v) && v >= lo; };
  for (const auto* colour : {&light.sun_color, &light.sky_color, &light.ground_color})
    for (const float c : *colour)
      if (!finite_at_least(c, 0)) fail("light: a colour of " + number_text(c) + ": expected finite, at least 0");
  const Vector3d sun = wide(light.sun_direction);
  if (!(std::abs(length(sun) - 1) <= kFrameTolerance))
    fail("light: the sun's direction " + vector_text(sun) + " is not a unit vector");
  if (!finite_at_least(light.sun_strength, 0) || !finite_at_least(light.exposure, 0) ||
      !finite_at_least(light.sky_reach, 0) || !finite_at_least(light.ray_offset, 0))
    fail("light: sun strength " + number_text(light.sun_strength) + ", exposure " + number_text(light.exposure) +
         ", sky reach " + number_text(light.sky_reach) + ", ray offset " + number_text(light.ray_offset) +
         ": expected finite numbers, at least 0");
  if (light.shadows > 1 || light.sky_rays > 65536)
    fail("light: shadows " + std::to_string(light.shadows) + ", sky rays " + std::to_string(light.sky_rays) +
         ": expected 0 or 1, and 0 .. 65536");
}

// Every number of the header and its arrays finite and in the range a build writes: a NaN fails
// every comparison, so a reader checking `tile_size == expected` later would pass it.
template <class Fail>
void check_header_numbers(const LdiPackInfo& info, Fail&& fail) {
  const auto in = [](float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  if (!in(info.tile_size, 1e-3f, 1e6f) || info.tile_size <= 0)
    fail("tile size " + number_text(info.tile_size) + ": expected meters in (0, 1e6]");
  if (!in(info.head_height, 0, 1e4f) || info.head_height <= 0)
    fail("head height " + number_text(info.head_height) + ": expected meters in (0, 10000]");
  if (!in(info.prism_top, -1e6f, 1e6f)) fail("prism top " + number_text(info.prism_top) + ": expected finite meters");
  if (!valid_field_of_view(info.fov_degrees))
    fail("field of view " + number_text(info.fov_degrees) + ": expected degrees in (0, 179]");
  if (info.image_width == 0 || info.image_width > 65535)
    fail("image width " + std::to_string(info.image_width) + ": expected 1 .. 65535 pixels");
  for (std::size_t l = 0; l < info.level_distances.size(); ++l) {
    const std::string level = "level " + std::to_string(l) + ": ";
    if (info.resolutions[l] == 0 || info.resolutions[l] > 65535)
      fail(level + "resolution " + std::to_string(info.resolutions[l]) + ": expected 1 .. 65535 pixels");
    if (!in(info.level_distances[l], 0, 1e9f) || info.level_distances[l] <= 0 ||
        (l > 0 && !(info.level_distances[l] >= info.level_distances[l - 1])))
      fail(level + "distance " + number_text(info.level_distances[l]) +
           ": expected positive meters, each level as far as the one before or farther");
    if (!in(info.elevations[l], -90, 90) || (l > 0 && info.elevations[l] > info.elevations[l - 1]))
      fail(level + "elevation " + number_text(info.elevations[l]) +
           ": expected degrees in [-90, 90], each level no higher than the one before");
  }
  for (std::size_t d = 0; d < info.azimuths.size(); ++d)
    if (!in(info.azimuths[d], 0, 360) || info.azimuths[d] == 360 ||
        (d > 0 && !(info.azimuths[d] > info.azimuths[d - 1])))
      fail("direction " + std::to_string(d) + ": azimuth " + number_text(info.azimuths[d]) +
           ": expected degrees in [0, 360), each direction after the one before");
  if (info.light) check_light_numbers(*info.light, fail);
}

}  // namespace

LdiPack::LdiPack(const std::filesystem::path& path) : path_(path) {
  auto fail = [&](const std::string& what) -> void { throw Error(path_, "", what); };
  // O_NONBLOCK: opening a FIFO would wait for a writer; the fstat below refuses it at once.
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) fail(std::string("cannot open: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    fail("not a regular file");
  }
  size_ = std::uint64_t(st.st_size);
  if (size_ < sizeof(PackHeader)) {
    ::close(fd);
    fail("truncated: " + std::to_string(size_) + " bytes, shorter than the " + std::to_string(sizeof(PackHeader)) +
         "-byte header (not an LDI pack?)");
  }
  void* map = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (map == MAP_FAILED) fail(std::string("cannot map: ") + std::strerror(errno));
  data_ = static_cast<const std::uint8_t*>(map);
  try {
    PackHeader h;
    std::memcpy(&h, data_, sizeof(h));
    if (std::memcmp(h.magic, kLdiPackMagic, sizeof(h.magic)) != 0) fail("bad magic: not a Wangscape LDI pack");
    if (h.version < kLdiPackOldestVersion || h.version > kLdiPackVersion)
      fail("version " + std::to_string(h.version) + "; this build reads version " +
           std::to_string(kLdiPackOldestVersion) + " or " + std::to_string(kLdiPackVersion));
    if (h.header_bytes != sizeof(PackHeader)) fail("header size " + std::to_string(h.header_bytes) + " is wrong");
    if (h.file_bytes != size_)
      fail((size_ < h.file_bytes ? "truncated: " : "trailing bytes: ") + std::string("the header says ") +
           std::to_string(h.file_bytes) + " bytes, the file has " + std::to_string(size_));
    if (h.tiles == 0 || h.levels == 0 || h.directions == 0 || h.tiles > kMaxTiles || h.levels > kMaxLevels ||
        h.directions > kMaxDirections)
      fail(std::to_string(h.tiles) + " tiles x " + std::to_string(h.levels) + " levels x " +
           std::to_string(h.directions) + " directions is out of range");
    for_each_info_field(h, info_, [](const auto& in_header, auto& in_info) { in_info = in_header; });
    if (h.version >= 3) info_.light.emplace();  // read below, once the index is known to fit
    const std::size_t n = std::size_t{h.tiles} * h.levels * h.directions;
    if (h.index_offset != index_offset_of(info_) || h.index_offset + n * sizeof(IndexEntry) > size_)
      fail("the index (at " + std::to_string(h.index_offset) + ", " + std::to_string(n) +
           " entries) is misplaced or runs past the end of the file");
    const std::uint8_t* arrays = data_ + sizeof(PackHeader);
    std::size_t at = 0;
    for_each_info_array(info_, [&](auto& values, std::uint32_t count) {
      values.resize(count);
      std::memcpy(values.data(), arrays + at, std::size_t{count} * 4);
      at += std::size_t{count} * 4;
    });
    if (info_.light) std::memcpy(&*info_.light, arrays + at, sizeof(LdiPackLight));
    check_header_numbers(info_, fail);

    const auto* index = reinterpret_cast<const IndexEntry*>(data_ + h.index_offset);
    const std::uint64_t data_start = h.index_offset + n * sizeof(IndexEntry);
    views_.resize(n);
    block_bytes_.resize(n);
    for (std::uint32_t t = 0; t < h.tiles; ++t)
      for (std::uint32_t l = 0; l < h.levels; ++l)
        for (std::uint32_t d = 0; d < h.directions; ++d) {
          const std::size_t e = entry_index(info_, t, l, d);
          const IndexEntry entry = index[e];
          const std::string which = "LDI (tile " + std::to_string(t) + ", level " + std::to_string(l) + ", direction " +
                                    std::to_string(d) + ")";
          auto block_fail = [&](const std::string& what) { throw Error(path_, which, what); };
          if (entry.offset % 8 != 0 || entry.offset < data_start || entry.offset > size_ ||
              entry.bytes > size_ - entry.offset)
            block_fail("offset " + std::to_string(entry.offset) + " + " + std::to_string(entry.bytes) +
                       " bytes is outside the data (" + std::to_string(data_start) + " .. " + std::to_string(size_) +
                       ")");
          views_[e] = validate_block(data_ + entry.offset, entry.bytes, t, l, d, info_, block_fail);
          block_bytes_[e] = entry.bytes;
        }
  } catch (...) {
    ::munmap(const_cast<std::uint8_t*>(data_), size_);
    throw;
  }
}

LdiPack::~LdiPack() { ::munmap(const_cast<std::uint8_t*>(data_), size_); }

LdiView LdiPack::ldi(std::uint32_t tile, std::uint32_t level, std::uint32_t direction) const {
  if (tile >= info_.tiles || level >= info_.levels || direction >= info_.directions)
    throw Error(path_, "",
                "no LDI (tile " + std::to_string(tile) + ", level " + std::to_string(level) + ", direction " +
                    std::to_string(direction) + ")");
  return views_[entry_index(info_, tile, level, direction)];
}

std::uint64_t LdiPack::ldi_bytes(std::uint32_t tile, std::uint32_t level, std::uint32_t direction) const {
  ldi(tile, level, direction);  // range check
  return block_bytes_[entry_index(info_, tile, level, direction)];
}

LdiPackStats ldi_pack_stats(const LdiPack& pack) {
  const LdiPackInfo& info = pack.info();
  LdiPackStats s;
  s.depth_pixels_per_level.assign(info.levels, 0);
  s.bytes_per_level.assign(info.levels, 0);
  s.layer_histogram.assign(256, 0);
  for (std::uint32_t t = 0; t < info.tiles; ++t)
    for (std::uint32_t l = 0; l < info.levels; ++l)
      for (std::uint32_t d = 0; d < info.directions; ++d) {
        const LdiView v = pack.ldi(t, l, d);
        const std::uint64_t pixels = std::uint64_t{v.frame->width} * v.frame->height;
        s.pixels += pixels;
        s.depth_pixels += v.depth_pixels.size();
        s.depth_pixels_per_level[l] += v.depth_pixels.size();
        s.bytes_per_level[l] += pack.ldi_bytes(t, l, d);
        s.layer_histogram[0] += pixels - v.counts.size();  // outside spans; zero counts inside add below
        for (std::uint8_t c : v.counts) ++s.layer_histogram[c];
      }
  while (s.layer_histogram.size() > 1 && s.layer_histogram.back() == 0) s.layer_histogram.pop_back();
  return s;
}

}  // namespace wangscape
