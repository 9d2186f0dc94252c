// Shared by the terrain tests: paths of the test DEMs (tests/data/dem, see its README), scratch directories, and small
// rasters written with GDAL itself (GeoTIFF, SRTM .hgt, PNG masks).
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

namespace wangscape::test {

inline std::filesystem::path test_dem(const std::string& name) {
  return std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "tests" / "data" / "dem" / name;
}
// The default scene's DEM, shipped in data/.
inline std::filesystem::path saint_helens() {
  return std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "data" / "SainteHelens.dem";
}
inline std::filesystem::path boulder() { return test_dem("SRTMGL3_boulder_CO_240x144.asc"); }

// A fresh, empty directory for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_terrain_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Writes a one-band raster through a GDAL driver (CreateCopy from memory). `value(col,
// row)` gives each pixel; `crs` is anything OGRSpatialReference::SetFromUserInput takes.
inline void write_raster(const std::filesystem::path& path, const char* driver, GDALDataType type, int width,
                         int height, const std::array<double, 6>& transform, const char* crs,
                         const std::function<double(int, int)>& value, int bands = 1) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDataset* source = mem->Create("", width, height, bands, type, nullptr);
  if (crs != nullptr) {
    OGRSpatialReference srs;
    srs.SetFromUserInput(crs);
    source->SetSpatialRef(&srs);
    source->SetGeoTransform(const_cast<double*>(transform.data()));
  }
  std::vector<double> pixels(std::size_t(width) * std::size_t(height));
  for (int b = 1; b <= bands; ++b) {
    for (int row = 0; row < height; ++row)
      for (int col = 0; col < width; ++col) pixels[std::size_t(row) * width + col] = value(col, row);
    if (source->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, width, height, pixels.data(), width, height, GDT_Float64, 0,
                                           0, nullptr) != CE_None)
      throw std::runtime_error("cannot fill the in-memory raster for " + path.string());
  }
  GDALDriver* out = GetGDALDriverManager()->GetDriverByName(driver);
  GDALDataset* copy = out->CreateCopy(path.c_str(), source, FALSE, nullptr, nullptr, nullptr);
  GDALClose(copy);
  GDALClose(source);
}

}  // namespace wangscape::test
