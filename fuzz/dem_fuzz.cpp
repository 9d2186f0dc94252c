// libFuzzer target: the DEM loader (read_dem through GDAL) and the terrain built on it (the ENU
// frame, the height lattice), on a DEM held in GDAL's in-memory files. The bytes are the DEM;
// a WGS 84 .prj sits beside it, so an ESRI ASCII grid gets as far as its heights.
#include <cpl_vsi.h>

#include "core/memory_budget.h"
#include "fuzz/fuzz_input.h"
#include "terrain/terrain.h"

namespace {

constexpr char kDemPath[] = "/vsimem/fuzz/dem.asc";
constexpr char kPrjPath[] = "/vsimem/fuzz/dem.prj";
constexpr char kWgs84Prj[] =
    "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",6378137.0,298.257223563]],"
    "PRIMEM[\"Greenwich\",0.0],UNIT[\"Degree\",0.0174532925199433]]";

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
  // A 1 KB header can declare a raster of a gigabyte, read (and filled) at ~1 s per execution;
  // at a 16 MiB limit such inputs are refused at once and the fuzzer explores the parsers.
  static const bool limit_lowered = [] {
    set_memory_limit_bytes_for_process(std::uint64_t{16} << 20);
    return true;
  }();
  (void)limit_lowered;
  // GDAL reads the buffer in place and never writes it (the file is opened read-only).
  VSILFILE* dem = VSIFileFromMemBuffer(kDemPath, const_cast<GByte*>(data), vsi_l_offset(size), FALSE);
  VSIFCloseL(dem);
  fuzz::refusals_are_fine([] {
    const Terrain terrain = Terrain::load(kDemPath);
    const Extent e = terrain.extent();
    (void)terrain.height(0.5 * (e.min_x + e.max_x), 0.5 * (e.min_y + e.max_y));
  });
  VSIUnlink(kDemPath);
  return 0;
}
