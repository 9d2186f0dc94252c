// Plants for a GIS: each instance as a point of an OGR layer (GeoPackage or GeoJSON) in the DEM's
// CRS or in WGS 84, with the fields species, variant, scale, yaw, height and rank; and the cover,
// plants per square metre in each DEM cell, as a GeoTIFF on the DEM's grid. `scatter --out
// FILE.gpkg|.geojson` and `[exports] gis` (DIR/plants.gpkg, DIR/cover.tif) write them. The files
// go through GDAL in terrain/gis_files.h (terrain/ is the folder that links GDAL); here the
// instances are turned from the scene's ENU frame into the file's CRS and counted into cells.
//
// The fields: species (its name: the [[species]] name, or the models' name, "sunflower" or the mesh
// file's stem; `scatter`: the class number of the filled set, "0", "1", ...), variant (the model
// variant; a camera-aware proxy counts as its full model's), scale (factor), yaw (radians,
// counter-clockwise from east, as in the CSV and PLY points), height (the ground's orthometric
// height under the plant, meters: the instance's z) and rank (the point's progressive order in
// [0, 1): the points with rank < d are Poisson at d times the density).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exporters/scene_writer.h"
#include "generator/instances.h"
#include "generator/poisson_tiles.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "terrain/gis_files.h"
#include "terrain/terrain.h"

namespace wangscape {

// What a plant's variant (InstanceBatch::variant) is called in a GIS file: per variant, its
// species (index into `species`) and the variant written.
struct PlantNames {
  std::vector<std::string> species;
  std::vector<std::uint16_t> species_of_variant;
  std::vector<std::uint16_t> written_variant;
};

// A scene's names: its [[species]] (or the one species of its models); proxies as their models.
PlantNames plant_names(const Scene& scene);
// A filled set's (scatter): the class of each variant, named by its number.
PlantNames plant_names(const FilledTileSet& filled);

// Instances to a plant layer: converted from ENU into `crs` (the DEM's CRS through the terrain's
// georeference lattice, exact to well under a millimetre; WGS 84 through the ENU frame).
class PlantPointWriter {
 public:
  // Throws Error naming `path` when GDAL cannot create it.
  PlantPointWriter(const Terrain& terrain, const std::filesystem::path& path, GisVectorFormat format, GisCrsChoice crs,
                   PlantNames names);
  void write(const InstanceBatch& batch);  // throws Error naming the file
  void commit();                           // the file appears under its name
  std::uint64_t count() const { return file_.count(); }

 private:
  const Terrain& terrain_;
  std::filesystem::path path_;
  GisCrsChoice crs_;
  PlantNames names_;
  PlantLayerFile file_;
  std::vector<double> x_, y_;
  std::vector<std::uint16_t> species_, variant_;
};

// Plants counted into the DEM's cells under `area` (ENU meters; a plant in the DEM cell whose
// centre is nearest), written as plants per square metre of each cell over the cells' bounding
// box of the planted ones (one cell when none is). Each cell's area is the grid's (terrain/
// gis_files.h: dem_cell_area_m2), so the values times the cell areas sum to the plant count.
class PlantCover {
 public:
  PlantCover(const Terrain& terrain, const Extent& area);
  void add(const InstanceBatch& batch);  // throws Error when a plant is off the DEM
  GisGrid grid() const;
  std::uint64_t count() const { return count_; }

 private:
  const Terrain& terrain_;
  int c0_ = 0, r0_ = 0, width_ = 0, height_ = 0;  // the counted window of DEM cells
  std::vector<std::uint32_t> counts_;
  std::uint64_t count_ = 0;
};

// The scene folder's GIS export: `dir`/plants.gpkg and `dir`/cover.tif (names from
// folder/scene_folder.h's caller). The scene must stand on a DEM.
class GisWriter : public SceneWriter {
 public:
  GisWriter(const Scene& scene, const std::filesystem::path& plants, const std::filesystem::path& cover,
            GisCrsChoice crs);
  void append(const InstanceBatch& batch) override;
  void finish(const StreamTotals& totals) override;

 private:
  std::filesystem::path cover_path_;
  std::unique_ptr<PlantPointWriter> points_;
  std::unique_ptr<PlantCover> cover_;
};

}  // namespace wangscape
