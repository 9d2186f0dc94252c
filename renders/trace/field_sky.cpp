#include "renders/trace/field_sky.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/atomic_file.h"
#include "core/binary_file.h"
#include "core/error.h"

namespace wangscape {

namespace {

constexpr char kMagic[8] = {'W', 'S', 'C', 'S', 'K', 'Y', '\r', '\n'};
constexpr std::uint32_t kVersion = 1;

// The placed flower nearest (x, y): searched in squares twice as wide each time, until one holds
// a flower no farther than the square's half side.
std::optional<std::array<double, 3>> nearest_flower(const SceneField& field, const Extent& area, double x, double y,
                                                    double start) {
  const double most = std::hypot(area.width(), area.height()) + start;
  for (double half = start;; half *= 2) {
    std::optional<std::array<double, 3>> best;
    double best_d2 = std::numeric_limits<double>::infinity();
    field.place_in({x - half, y - half, x + half, y + half}, [&](const InstanceBatch& batch) {
      for (std::size_t i = 0; i < batch.size(); ++i) {
        const double dx = batch.x[i] - x, dy = batch.y[i] - y, d2 = dx * dx + dy * dy;
        if (d2 < best_d2) best_d2 = d2, best = std::array<double, 3>{batch.x[i], batch.y[i], batch.z[i]};
      }
    });
    if ((best && best_d2 <= half * half) || half > most) return best;
  }
}

}  // namespace

SceneTracer::SkyShares bake_field_sky(const Scene& scene, const ShadingSettings& shading) {
  if (shading.ao_rays <= 0 || !scene.field || scene.models.empty()) return {};
  const SceneField& field = *scene.field;
  const Extent& area = scene.field_area;
  const double s = field.placement.tile_size;
  const auto at = nearest_flower(field, area, (area.min_x + area.max_x) / 2, (area.min_y + area.max_y) / 2, s);
  if (!at) return {};
  const auto [x, y, z] = *at;
  const double reach = kFieldSkyReach + 1.5 * s;
  const Extent window{std::floor((x - reach) / s) * s, std::floor((y - reach) / s) * s, std::ceil((x + reach) / s) * s,
                      std::ceil((y + reach) / s) * s};
  SceneTracer tracer(scene, {x, y, z}, SceneTracer::Layout::part);
  tracer.set_flowers([&](const InstanceSink& sink) { field.place_in(window, sink); });
  tracer.bake_sky(shading);
  return tracer.sky_shares();
}

void write_sky_shares(const std::filesystem::path& path, const SceneTracer::SkyShares& shares) {
  static_assert(std::endian::native == std::endian::little, "the file's floats are written as the machine holds them");
  AtomicFile file(path);
  std::ostream& out = file.stream();
  put_binary_header(out, kMagic, kVersion);
  put_u32(out, std::uint32_t(shares.size()));
  for (const auto& model : shares) put_u32(out, std::uint32_t(model.size()));
  for (const auto& model : shares)
    out.write(reinterpret_cast<const char*>(model.data()), std::streamsize(model.size() * sizeof(model[0])));
  file.commit();
}

SceneTracer::SkyShares read_sky_shares(const std::filesystem::path& path, const Scene& scene) {
  BinaryReader in(path, kMagic, kVersion, "sky shares");
  const std::uint32_t models = in.u32("the sky shares' header");
  if (models != 0 && models != scene.models.size())  // 0: none estimated (no sky rays, no flowers)
    in.fail(std::to_string(models) + " models: expected the scene's " + std::to_string(scene.models.size()) +
            " (rebuild the folder)");
  SceneTracer::SkyShares shares(models);
  for (std::uint32_t v = 0; v < models; ++v) {
    const std::uint32_t vertices = in.u32("the sky shares' header");
    if (vertices != scene.models[v].positions.size())
      in.fail("model " + std::to_string(v) + ": " + std::to_string(vertices) + " vertices, expected " +
              std::to_string(scene.models[v].positions.size()) + " (rebuild the folder)");
    shares[v].resize(vertices);
  }
  for (std::uint32_t v = 0; v < models; ++v) {
    auto& model = shares[v];
    in.read(model.data(), model.size() * sizeof(model[0]), "model " + std::to_string(v) + "'s shares");
    for (std::size_t i = 0; i < model.size(); ++i)
      for (const float share : model[i])
        if (!(share >= 0.0f && share <= 1.0f))
          in.fail("model " + std::to_string(v) + ", vertex " + std::to_string(i) +
                  ": a share outside [0, 1] or not a number");
  }
  in.expect_end("its models' shares");
  return shares;
}

}  // namespace wangscape
