#include "exporters/point_writer.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>

#include "core/number_text.h"

namespace wangscape {

namespace {

constexpr int kCountWidth = 20;  // digits reserved for the PLY vertex count (fits any uint64)

template <class T>
void append_le(std::string& out, T value) {
  static_assert(std::endian::native == std::endian::little, "PLY writer assumes a little-endian host");
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

PointFileFormat point_file_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".csv") return PointFileFormat::csv;
  if (ext == ".ply") return PointFileFormat::ply;
  if (ext == ".gpkg") return PointFileFormat::geopackage;
  if (ext == ".geojson") return PointFileFormat::geojson;
  throw Error(
      path, "",
      (ext.empty() ? std::string("has no extension") : "has the extension '" + path.extension().string() + "'") +
          ": expected .csv, .ply (points in the scene's ENU frame), .gpkg (GeoPackage) or .geojson (GeoJSON)");
}

PointWriter::PointWriter(const std::filesystem::path& path) : file_(path), format_(point_file_format(path)) {
  if (format_ != PointFileFormat::csv && format_ != PointFileFormat::ply)
    throw Error(path, "", "is a GIS layer: write it with exporters/gis_writer.h");
  std::ofstream& out = file_.stream();
  if (format_ == PointFileFormat::csv) {
    out << "x,y,z,variant,yaw,scale,tile\n";
  } else {
    out << "ply\nformat binary_little_endian 1.0\n"
           "comment wangscape instances: x y z in meters (east, north, up), yaw in radians\n"
           "element vertex ";
    count_field_ = static_cast<std::streamoff>(out.tellp());
    out << std::string(kCountWidth, ' ') << "\n"
        << "property float x\nproperty float y\nproperty float z\nproperty ushort variant\n"
           "property float yaw\nproperty float scale\nproperty uint tile\nend_header\n";
  }
  if (!out) throw Error("point file '" + path.string() + "': cannot write the header");
}

void PointWriter::write(const InstanceBatch& b) {
  buffer_.clear();
  if (format_ == PointFileFormat::csv) {
    buffer_.reserve(b.size() * 64);
    for (std::size_t k = 0; k < b.size(); ++k) {
      append_number(buffer_, b.x[k]);
      buffer_ += ',';
      append_number(buffer_, b.y[k]);
      buffer_ += ',';
      append_number(buffer_, b.z[k]);
      buffer_ += ',';
      append_number(buffer_, b.variant[k]);
      buffer_ += ',';
      append_number(buffer_, b.yaw[k]);
      buffer_ += ',';
      append_number(buffer_, b.scale[k]);
      buffer_ += ',';
      append_number(buffer_, b.tile[k]);
      buffer_ += '\n';
    }
  } else {
    buffer_.reserve(b.size() * 26);
    for (std::size_t k = 0; k < b.size(); ++k) {
      append_le(buffer_, b.x[k]);
      append_le(buffer_, b.y[k]);
      append_le(buffer_, b.z[k]);
      append_le(buffer_, b.variant[k]);
      append_le(buffer_, b.yaw[k]);
      append_le(buffer_, b.scale[k]);
      append_le(buffer_, b.tile[k]);
    }
  }
  file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  if (!file_.stream()) throw Error("point file '" + file_.path().string() + "': write failed");
  count_ += b.size();
}

void PointWriter::commit() {
  if (format_ == PointFileFormat::ply) {
    // The count is known only now: it goes into the field reserved in the header, left-aligned
    // and padded with spaces (PLY readers split header lines on whitespace).
    std::string digits;
    append_number(digits, count_);
    digits.resize(kCountWidth, ' ');
    std::ofstream& out = file_.stream();
    const auto end = out.tellp();
    out.seekp(count_field_);
    out.write(digits.data(), kCountWidth);
    out.seekp(end);
  }
  file_.commit();
}

}  // namespace wangscape
