// What a scene makes of its [[species]] (issue 26): the models of every species one after the
// other (Scene::models; species s's variants are class_variant_range of the filled set), the
// classes of the one Poisson fill (radii in tile sides), and each species' rules and density
// asked about every placed point. Without [[species]] none of this is used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "generator/poisson_tiles.h"
#include "scene/scene_file.h"
#include "scene/scene_ground.h"
#include "templates/mesh.h"
#include "terrain/mask.h"

namespace wangscape {

// The models of every species in file order, each species' variants in a row; a plant kind's
// budget is capped at `budget_cap` (proxies) but kept within the kind's range. `tight_radii`
// (optional) receives each species' largest horizontal extent, meters. Throws Error naming the
// species' key.
std::vector<Mesh> make_species_models(const SceneConfig& config,
                                      std::size_t budget_cap = std::numeric_limits<std::size_t>::max(),
                                      std::vector<double>* tight_radii = nullptr);

// The fill's classes: share, radii (meters / tile size; the tight radius defaults to the
// models' extent `tight_radii`), variants, edge objects, exclusions by index. `fill`: the fill
// they join (points per tile, dart rho). Throws Error naming the species' key (file:line) where
// the fill would refuse them: a radius, an exclusion or a distance the fill keeps (packing radii
// plus exclusion, a species' own spacing at its share) not below the fill's limits.
std::vector<PoissonClass> species_classes(const SceneConfig& config, const std::vector<double>& tight_radii,
                                          PoissonFillOptions fill);

// Piecewise-linear y of x over `curve` (x increasing), held flat beyond its ends; 1 when empty.
double density_curve_at(const std::vector<std::array<double, 2>>& curve, double x);

// The compass aspect (degrees clockwise from north, 0..360) a ground of unit normal `n` faces:
// the downhill direction.
double aspect_degrees(const std::array<double, 3>& n);
// Whether compass `aspect` lies in [from, to] going clockwise (wrapping past north).
bool aspect_in_range(double aspect, double from, double to);

// Each species' rules (height, slope, aspect, painted mask) and density over a ground.
// Thread-safe (const) once built; keeps a copy of the ground (a shared handle).
class SpeciesRules {
 public:
  SpeciesRules(const SceneConfig& config, const SceneGround& ground);
  // Whether a point of `species` with progressive `rank` stands at (x, y) on ground z (meters):
  // every rule holds and rank < the density there.
  bool keeps(double x, double y, double z, std::uint8_t species, float rank) const;
  // The species' density (0..1) at (x, y, z) where its rules (height, slope, aspect, mask) let it
  // grow, else 0.
  double density_where_grows(std::uint8_t species, double x, double y, double z) const;
  // density_where_grows of every species at (x, y, z) into densities[species] (size() of them),
  // the ground's slope and normal there read once for all.
  void densities_where_grow(double x, double y, double z, std::span<double> densities) const;
  // How many species there are, and their names, in file order (the fill's class order).
  std::size_t size() const { return rules_.size(); }
  std::vector<std::string> names() const;

 private:
  struct Rule {
    SpeciesConfig config;
    std::optional<GroundMask> mask;
    bool needs_slope = false;
  };
  class GroundAt;  // the ground's slope and normal at one place, each read at most once
  static double density_of(const Rule& rule, double x, double y, double z, GroundAt& ground);
  std::vector<Rule> rules_;
  SceneGround ground_;
};

}  // namespace wangscape
