#include "templates/plants.h"

#include <array>

#include "templates/grass.h"
#include "templates/sunflower.h"
#include "templates/wildflower.h"

namespace wangscape {
namespace {

constexpr std::array<std::pair<PlantKind, std::string_view>, 3> kKinds = {
    {{PlantKind::sunflower, "sunflower"}, {PlantKind::grass, "grass"}, {PlantKind::wildflower, "wildflower"}}};

PlantModel make_plant(PlantKind kind, std::uint64_t seed, int variant, std::size_t budget) {
  switch (kind) {
    case PlantKind::sunflower: {
      SunflowerModel sunflower = make_sunflower(seed, variant, budget);
      return {std::move(sunflower.mesh), sunflower.extent};
    }
    case PlantKind::grass:
      return make_grass_clump(seed, variant, budget);
    case PlantKind::wildflower:
      return make_wildflower(seed, variant, budget);
  }
  return {};
}

}  // namespace

std::optional<PlantKind> find_plant_kind(std::string_view name) {
  for (const auto& [kind, kind_name] : kKinds)
    if (kind_name == name) return kind;
  return std::nullopt;
}

std::string_view plant_kind_name(PlantKind kind) {
  for (const auto& [k, name] : kKinds)
    if (k == kind) return name;
  return "?";
}

std::string plant_kind_names() { return "\"sunflower\", \"grass\" or \"wildflower\""; }

TriangleBudgetRange triangle_budget_range(PlantKind kind) {
  switch (kind) {
    case PlantKind::sunflower:
      return {kSunflowerMinimumTriangleBudget, kSunflowerMaximumTriangleBudget, 6000};
    case PlantKind::grass:
      return {kGrassMinimumTriangleBudget, kGrassMaximumTriangleBudget, kGrassDefaultTriangleBudget};
    case PlantKind::wildflower:
      return {kWildflowerMinimumTriangleBudget, kWildflowerMaximumTriangleBudget, kWildflowerDefaultTriangleBudget};
  }
  return {};
}

std::vector<PlantModel> make_plant_variants(PlantKind kind, std::uint64_t seed, int count, std::size_t triangle_budget,
                                            double scale) {
  if (count < 1)
    throw Error(std::string(plant_kind_name(kind)) + " variant count " + std::to_string(count) +
                " is invalid: expected >= 1");
  std::vector<PlantModel> models;
  models.reserve(std::size_t(count));
  for (int variant = 0; variant < count; ++variant) {
    PlantModel model = make_plant(kind, seed, variant, triangle_budget);
    if (scale != 1.0) {
      for (auto& p : model.mesh.positions)
        for (auto& c : p) c = static_cast<float>(c * scale);
      model.extent = measure_extent(model.mesh);
    }
    models.push_back(std::move(model));
  }
  return models;
}

}  // namespace wangscape
