// Instances to a point file, batch by batch (any scatter: plane or DEM): CSV with the header
// `x,y,z,variant,yaw,scale,tile` (meters, radians; shortest round-trip numbers, locale-free) when
// the name ends in .csv, or binary little-endian PLY for .ply (vertex element with float x, y, z,
// ushort variant, float yaw, float scale, uint tile). Written atomically: nothing appears at `path`
// unless commit() succeeds. GeoPackage (.gpkg) and GeoJSON (.geojson) are the GIS layers of
// exporters/gis_writer.h, which need a DEM.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "core/atomic_file.h"
#include "generator/instances.h"

namespace wangscape {

enum class PointFileFormat { csv, ply, geopackage, geojson };

// By the extension, in any case: .csv, .ply, .gpkg, .geojson. Throws Error naming the file and the
// extensions expected for any other (or none).
PointFileFormat point_file_format(const std::filesystem::path& path);

class PointWriter {
 public:
  // A .csv or .ply file (point_file_format); throws Error naming it for any other.
  explicit PointWriter(const std::filesystem::path& path);
  PointWriter(const PointWriter&) = delete;
  PointWriter& operator=(const PointWriter&) = delete;

  // Appends the batch. Throws Error naming the file when writing fails.
  void write(const InstanceBatch& batch);
  // Completes the file (the PLY vertex count) and renames it into place.
  void commit();

  std::uint64_t count() const { return count_; }
  PointFileFormat format() const { return format_; }

 private:
  AtomicFile file_;
  PointFileFormat format_;
  std::uint64_t count_ = 0;
  std::streamoff count_field_ = 0;  // PLY: where the padded vertex count goes
  std::string buffer_;
};

}  // namespace wangscape
