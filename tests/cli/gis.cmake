# The outputs a GIS opens (issue 38, part 6), checked with GDAL's own programs (ogrinfo, gdalinfo,
# gdalsrsinfo, gdal_translate): scatter's GeoPackage and GeoJSON layers in the DEM's CRS or WGS 84,
# the build's plants.gpkg and cover.tif ([exports] gis), the masks from georeferenced files (issue
# 38, part 5: polygons, a raster in another CRS, area_latlon), and the refusals. One MODE per test
# (gis_check.py says what each checks).
find_program(gis_python3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
foreach(mode IN ITEMS scatter_gpkg scatter_geojson scatter_wgs84 build bad_extension needs_dem scene_needs_dem
                      mask_polygons area_latlon mask_raster mask_bad)
  add_test(NAME cli_gis_${mode}
    COMMAND ${gis_python3} ${CMAKE_CURRENT_LIST_DIR}/gis_check.py ${WANGSCAPE_BIN} ${CLI_SCRATCH}/gis_${mode} ${mode}
            ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli_gis_${mode} PROPERTIES LABELS cli TIMEOUT 900)
endforeach()
