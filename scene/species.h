// What a scene makes of its [[species]] (issue 26): the models of every species one after the
// other (Scene::models; species s's variants are class_variant_range of the filled set), the
// classes of the one Poisson fill (radii in tile sides), and each species' rules and density
// asked about every placed point. Without [[species]] none of this is used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "generator/poisson_tiles.h"
#include "scene/scene_file.h"
#include "scene/scene_ground.h"
#include "templates/mesh.h"
#include "templates/stand_in.h"
#include "terrain/mask.h"

namespace wangscape {

// The models of every species.
struct SpeciesModels {
  std::vector<Mesh> models;         // every species' variants, in file order, each species' in a row
  std::vector<int> variants;        // per species: how many of `models` are its
  std::vector<double> tight_radii;  // per species: its largest model's horizontal extent, meters
};

// Each species' variants: a plant kind's `variants` of the kind's budget, a user's models'
// variants (load_user_variants), each named "<species>_<variant>". Throws Error naming the
// species' key.
SpeciesModels make_species_models(const SceneConfig& config);

// The camera-aware export's proxies of `models` (make_species_models' models, `variants` of each
// species), in their order: a plant kind's variants again at a budget capped at `budget_cap`
// (within the kind's range), a user model's stand-ins of at most `budget_cap` triangles
// (make_stand_ins; their figures appended to `stand_ins`).
std::vector<Mesh> make_species_proxies(const SceneConfig& config, std::span<const Mesh> models,
                                       const std::vector<int>& variants, std::size_t budget_cap,
                                       std::vector<StandInFigures>& stand_ins);

// The variants of a user's models `mesh` (files, folders; objects as variants or not), turned
// and scaled into model space with the file's origin as ground contact. Throws Error naming
// `key` of the scene file and the file at fault.
std::vector<Mesh> load_user_variants(const SceneConfig& config, const std::string& key,
                                     const std::vector<std::filesystem::path>& mesh, bool y_up, bool objects_variants,
                                     double scale);

// The fill's classes: share, radii (meters / tile size; the tight radius defaults to the
// models' extent models.tight_radii), variants (models.variants), edge objects, exclusions by index. `fill`: the fill
// they join (points per tile, dart rho). Throws Error naming the species' key (file:line) where
// the fill would refuse them: a radius, an exclusion or a distance the fill keeps (packing radii
// plus exclusion, a species' own spacing at its share) not below the fill's limits.
std::vector<PoissonClass> species_classes(const SceneConfig& config, const SpeciesModels& models,
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
