// The procedural plant kinds a scene's species may name, and their variants as meshes: one
// place that knows each kind's generator, triangle budgets and default budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "templates/mesh.h"

namespace wangscape {

enum class PlantKind { sunflower, grass, wildflower };

// "sunflower", "grass" or "wildflower" (the scene file's species.model), or nothing.
std::optional<PlantKind> find_plant_kind(std::string_view name);
std::string_view plant_kind_name(PlantKind kind);
// Every kind's name, for messages: "\"sunflower\", \"grass\" or \"wildflower\"".
std::string plant_kind_names();

struct TriangleBudgetRange {
  std::size_t minimum, maximum;  // what the generator accepts, per model
  std::size_t default_budget;    // a meadow's: close-ups hold, a tile stays near Shade's 62,000
};
TriangleBudgetRange triangle_budget_range(PlantKind kind);

// `count` variants (0 .. count-1) of `kind` drawn from `seed`, each with at most
// `triangle_budget` triangles, scaled by `scale`. Throws Error for a count below 1 or a
// budget outside the kind's range. Thread-safe.
std::vector<PlantModel> make_plant_variants(PlantKind kind, std::uint64_t seed, int count, std::size_t triangle_budget,
                                            double scale = 1.0);

}  // namespace wangscape
