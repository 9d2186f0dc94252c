#include "scene/species.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/number_text.h"
#include "templates/model_variants.h"
#include "templates/plants.h"
#include "terrain/terrain.h"

namespace wangscape {

std::vector<Mesh> load_user_variants(const SceneConfig& config, const std::string& key,
                                     const std::vector<std::filesystem::path>& mesh, bool y_up, bool objects_variants,
                                     double scale) {
  UserModelOptions options;
  options.scale = static_cast<float>(scale);
  options.y_up = y_up;
  options.ground_at_origin = false;  // the file's origin is the model's ground contact point
  try {
    return load_model_variants(mesh, objects_variants, options);
  } catch (const Error& e) {
    throw config.error_at(key, e.what());  // naming the file at fault: the key may name several
  }
}

namespace {

// A plant kind's variants for `species`, its budget capped at `budget_cap` within the kind's range.
std::vector<PlantModel> kind_variants(const SceneConfig& config, const SpeciesConfig& species, std::size_t budget_cap) {
  const PlantKind kind = *find_plant_kind(species.model);
  const auto range = triangle_budget_range(kind);
  const std::size_t budget = std::clamp(std::min(species.triangle_budget.value_or(range.default_budget), budget_cap),
                                        range.minimum, range.maximum);
  auto variants =
      make_plant_variants(kind, species.seed.value_or(config.models.seed), species.variants, budget, species.scale);
  // Named by species: two kinds' "petal"s are different materials in every exporter.
  for (PlantModel& model : variants)
    for (Material& material : model.mesh.materials) material.name = species.name + " " + material.name;
  return variants;
}

}  // namespace

SpeciesModels make_species_models(const SceneConfig& config) {
  SpeciesModels out;
  for (const SpeciesConfig& species : config.species) {
    std::vector<Mesh> variants;
    if (!species.mesh.empty()) {
      variants = load_user_variants(config, "species." + species.name + ".model", species.mesh, species.mesh_y_up,
                                    species.mesh_objects_variants, species.scale);
    } else {
      for (PlantModel& model : kind_variants(config, species, std::numeric_limits<std::size_t>::max()))
        variants.push_back(std::move(model.mesh));
    }
    double radius = 0;
    for (std::size_t v = 0; v < variants.size(); ++v) {
      radius = std::max<double>(radius, measure_extent(variants[v]).radius);
      // Named by species and variant ("dandelion_3"): the exporters name the model so.
      variants[v].name = species.name + "_" + std::to_string(v);
      out.models.push_back(std::move(variants[v]));
    }
    out.variants.push_back(int(variants.size()));
    out.tight_radii.push_back(radius);
  }
  return out;
}

std::vector<Mesh> make_species_proxies(const SceneConfig& config, std::span<const Mesh> models,
                                       const std::vector<int>& variants, std::size_t budget_cap,
                                       std::vector<StandInFigures>& stand_ins) {
  std::vector<Mesh> proxies;
  std::size_t first = 0;
  for (std::size_t s = 0; s < config.species.size(); ++s) {
    const SpeciesConfig& species = config.species[s];
    const std::span<const Mesh> own = models.subspan(first, std::size_t(variants[s]));
    first += own.size();
    if (!species.mesh.empty()) {
      StandInOptions options;
      options.max_triangles = budget_cap;
      for (Mesh& stand_in : make_stand_ins(own, options, stand_ins)) proxies.push_back(std::move(stand_in));
      continue;
    }
    std::size_t v = 0;
    for (PlantModel& model : kind_variants(config, species, budget_cap)) {
      model.mesh.name = own[v++].name + " proxy";
      proxies.push_back(std::move(model.mesh));
    }
  }
  return proxies;
}

std::vector<PoissonClass> species_classes(const SceneConfig& config, const SpeciesModels& models,
                                          PoissonFillOptions fill) {
  const double tile = config.tiles.tile_size;
  const auto in_meters = [tile](double tile_sides) { return significant_text(tile_sides * tile, 4) + " m"; };
  // The fill's limits in meters, named by the species' key (the fill knows only class numbers).
  const auto too_far = [&](const std::string& key, const std::string& what, double most, const std::string& hint = "") {
    return config.error_at(
        key, what + "; a tile of " + in_meters(1) + " (tiles.tile_size) takes less than " + in_meters(most) + hint);
  };
  // The largest a flower grows with the scale jitter.
  const double grown = 1 + config.models.scale_jitter;
  std::vector<PoissonClass> classes;
  for (std::size_t s = 0; s < config.species.size(); ++s) {
    const SpeciesConfig& species = config.species[s];
    PoissonClass c;
    c.share = species.share;
    c.variants = models.variants[s];
    c.edge_objects = species.edge_objects;
    c.tight_radius = species.tight_radius.value_or(models.tight_radii[s] * grown) / tile;
    c.packing_radius = species.packing_radius.value_or(0) / tile;
    const std::string key = "species." + species.name + ".";
    const auto limit = [&](double radius, const std::string& what, double most) {
      if (radius >= most) throw too_far(key + what, "is " + in_meters(radius), most);
    };
    limit(c.tight_radius, species.tight_radius ? "tight_radius" : "model", kMaxClassRadius);
    limit(c.packing_radius, "packing_radius", kMaxClassRadius);
    if (!species.exclusion.empty()) {
      c.exclusion.assign(config.species.size(), 0.0);
      for (const auto& [other, meters] : species.exclusion)
        for (std::size_t k = 0; k < config.species.size(); ++k)
          if (config.species[k].name == other) c.exclusion[k] = meters / tile;
      for (const double e : c.exclusion) limit(e, "exclusion", kMaxClassDistance);
    }
    classes.push_back(std::move(c));
  }
  // Each radius fits, but the distances the fill keeps between two species (packing radii plus
  // exclusion) or within one (its own spacing at its share) must fit a tile too: refused here,
  // named by the species' key, not by the fill with class numbers.
  fill.classes = classes;
  if (const std::optional<ClassesTooFar> far = classes_too_far(fill)) {
    const std::size_t a = far->a, b = far->b;
    const double d = far->distance;
    const auto exclusion = [&](std::size_t from, std::size_t to) {
      return to < classes[from].exclusion.size() ? classes[from].exclusion[to] : 0.0;
    };
    const std::string &name_a = config.species[a].name, &name_b = config.species[b].name;
    if (a == b) {
      double total_share = 0;
      for (const PoissonClass& c : classes) total_share += c.share;
      const std::string share_key = "species." + name_a + ".share";
      throw too_far(config.key_lines.contains(share_key) ? share_key : "tiles.points_per_tile",
                    "leaves about " + significant_text(fill.points_per_tile * classes[a].share / total_share, 3) +
                        " points of '" + name_a + "' a tile (its share of tiles.points_per_tile " +
                        std::to_string(fill.points_per_tile) + "), " + in_meters(d) + " apart",
                    kMaxClassDistance, ": a larger share or more points per tile");
    }
    const std::size_t by = exclusion(a, b) >= exclusion(b, a) ? a : b, to = by == a ? b : a;
    throw too_far("species." + config.species[by].name + ".exclusion",
                  "keeps '" + name_a + "' and '" + name_b + "' " + in_meters(d) + " apart (their packing radii " +
                      in_meters(d - exclusion(by, to)) + " together, plus " + in_meters(exclusion(by, to)) + ")",
                  kMaxClassDistance);
  }
  return classes;
}

double density_curve_at(const std::vector<std::array<double, 2>>& curve, double x) {
  if (curve.empty()) return 1;
  if (x <= curve.front()[0]) return curve.front()[1];
  if (x >= curve.back()[0]) return curve.back()[1];
  const auto after = std::upper_bound(curve.begin(), curve.end(), x,
                                      [](double value, const std::array<double, 2>& p) { return value < p[0]; });
  const auto& a = *(after - 1);
  const auto& b = *after;
  return a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]);
}

double aspect_degrees(const std::array<double, 3>& n) {
  // The normal leans downhill: its horizontal part points where the slope faces.
  const double compass = std::atan2(n[0], n[1]) * 180 / std::numbers::pi;
  return compass < 0 ? compass + 360 : compass;
}

bool aspect_in_range(double aspect, double from, double to) {
  const auto wrap = [](double a) { return a - 360 * std::floor(a / 360); };
  const double span = wrap(to - from);
  return wrap(aspect - from) <= span;
}

SpeciesRules::SpeciesRules(const SceneConfig& config, const SceneGround& ground) : ground_(ground) {
  for (const SpeciesConfig& species : config.species) {
    Rule rule;
    rule.config = species;
    rule.needs_slope = species.min_slope || species.max_slope || !species.density_by_slope.empty();
    if (!species.mask.empty()) {
      if (!ground.terrain())
        throw config.error_at("species." + species.name + ".mask", "needs a DEM (terrain.dem) to be stretched over");
      try {
        rule.mask = GroundMask::painted(species.mask, ground.terrain()->extent());
      } catch (const Error& e) {
        throw config.error_at("species." + species.name + ".mask", e.message());
      }
    }
    rules_.push_back(std::move(rule));
  }
}

std::vector<std::string> SpeciesRules::names() const {
  std::vector<std::string> names;
  for (const Rule& rule : rules_) names.push_back(rule.config.name);
  return names;
}

// The ground at one place as the rules read it: sampled at most once, for its slope and normal both.
class SpeciesRules::GroundAt {
 public:
  GroundAt(const SceneGround& ground, double x, double y) : ground_(ground), x_(x), y_(y) {}
  std::optional<double> slope() {
    const auto& s = sample();
    return s ? std::optional<double>(s->slope_degrees()) : std::nullopt;
  }
  std::optional<std::array<double, 3>> normal() {
    const auto& s = sample();
    return s ? std::optional<std::array<double, 3>>(s->normal()) : std::nullopt;
  }

 private:
  const std::optional<GroundSample>& sample() {
    if (!sample_) sample_ = ground_.sample(x_, y_);
    return *sample_;
  }
  const SceneGround& ground_;
  double x_, y_;
  std::optional<std::optional<GroundSample>> sample_;
};

double SpeciesRules::density_of(const Rule& rule, double x, double y, double z, GroundAt& ground) {
  const SpeciesConfig& c = rule.config;
  if ((c.min_height && z < *c.min_height) || (c.max_height && z > *c.max_height)) return 0;
  if (rule.mask && !rule.mask->allows(x, y)) return 0;
  std::optional<double> slope;
  if (rule.needs_slope) slope = ground.slope();
  if ((c.min_slope || c.max_slope) &&
      (!slope || (c.min_slope && *slope < *c.min_slope) || (c.max_slope && *slope > *c.max_slope)))
    return 0;
  if (c.aspect) {
    // Ground flatter than a degree faces nowhere in particular: every aspect range holds there.
    const auto n = ground.normal();
    if (!n) return 0;
    const bool flat = (*n)[2] > std::cos(std::numbers::pi / 180);
    if (!flat && !aspect_in_range(aspect_degrees(*n), (*c.aspect)[0], (*c.aspect)[1])) return 0;
  }
  double d = density_curve_at(c.density_by_height, z);
  if (!c.density_by_slope.empty()) d *= density_curve_at(c.density_by_slope, slope.value_or(0));
  return d;
}

double SpeciesRules::density_where_grows(std::uint8_t species, double x, double y, double z) const {
  GroundAt ground(ground_, x, y);
  return density_of(rules_[species], x, y, z, ground);
}

void SpeciesRules::densities_where_grow(double x, double y, double z, std::span<double> densities) const {
  GroundAt ground(ground_, x, y);
  for (std::size_t s = 0; s < rules_.size(); ++s) densities[s] = density_of(rules_[s], x, y, z, ground);
}

bool SpeciesRules::keeps(double x, double y, double z, std::uint8_t species, float rank) const {
  if (species >= rules_.size()) return false;
  return double(rank) < density_where_grows(species, x, y, z);
}

}  // namespace wangscape
