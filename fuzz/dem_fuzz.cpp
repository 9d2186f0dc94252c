// libFuzzer target: the DEM loader (read_dem through GDAL) and the terrain built on it (the ENU
// frame, the height lattice), on a DEM held in GDAL's in-memory files. The bytes are the DEM;
// a WGS 84 .prj sits beside it, so an ESRI ASCII grid gets as far as its heights.
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal.h>

#include "core/memory_budget.h"
#include "fuzz/fuzz_input.h"
#include "terrain/terrain.h"

namespace {

constexpr char kDemPath[] = "/vsimem/fuzz/dem.asc";
constexpr char kPrjPath[] = "/vsimem/fuzz/dem.prj";
constexpr char kWgs84Prj[] =
    "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",6378137.0,298.257223563]],"
    "PRIMEM[\"Greenwich\",0.0],UNIT[\"Degree\",0.0174532925199433]]";

// The scene frame converts every boundary sample (2 per row and per column) and every lattice
// node through PROJ and GeographicLib, so long legal strips cost far more than their bytes and
// held the fuzzer back. Grids past these sizes are parsed (GDALOpen reads the header) but not
// loaded; the large-grid paths are covered by the terrain tests.
constexpr int kMaxFuzzEdgeSum = 4096;                               // width + height, cells
constexpr double kMaxFuzzCells = 65536;                             // width x height
constexpr std::uint64_t kFuzzMemoryLimit = std::uint64_t{1} << 20;  // bytes: a lattice of <= 32 K nodes

bool small_enough_to_load(const char* path) {
  static const bool registered = [] {
    GDALAllRegister();
    return true;
  }();
  (void)registered;
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetH dataset = GDALOpen(path, GA_ReadOnly);
  CPLPopErrorHandler();
  if (dataset == nullptr) return true;  // let the loader refuse it with its own message
  // As doubles: a header may declare sizes whose int sum overflows (found by this fuzzer).
  const double width = GDALGetRasterXSize(dataset), height = GDALGetRasterYSize(dataset);
  GDALClose(dataset);
  return width + height <= kMaxFuzzEdgeSum && width * height <= kMaxFuzzCells;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  static const bool prj_written = [] {
    VSILFILE* prj = VSIFileFromMemBuffer(kPrjPath, reinterpret_cast<GByte*>(const_cast<char*>(kWgs84Prj)),
                                         sizeof kWgs84Prj - 1, FALSE);
    VSIFCloseL(prj);
    return prj != nullptr;
  }();
  if (!prj_written) std::abort();
  // A 1 KB header can declare a raster of a gigabyte, read (and filled) at ~1 s per execution,
  // or a small grid a lattice of 10^5 nodes: at a 1 MiB limit such inputs are refused at once
  // and the fuzzer explores the parsers.
  static const bool limit_lowered = [] {
    set_memory_limit_bytes_for_process(kFuzzMemoryLimit);
    return true;
  }();
  (void)limit_lowered;
  // GDAL reads the buffer in place and never writes it (the file is opened read-only).
  VSILFILE* dem = VSIFileFromMemBuffer(kDemPath, const_cast<GByte*>(data), vsi_l_offset(size), FALSE);
  VSIFCloseL(dem);
  if (small_enough_to_load(kDemPath))
    fuzz::refusals_are_fine([] {
      const Terrain terrain = Terrain::load(kDemPath);
      const Extent e = terrain.extent();
      (void)terrain.height(0.5 * (e.min_x + e.max_x), 0.5 * (e.min_y + e.max_y));
    });
  VSIUnlink(kDemPath);
  return 0;
}
