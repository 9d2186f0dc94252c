"""gis_check.py WANGSCAPE SCRATCH MODE SOURCE_DIR: the GIS outputs (issue 38, part 6) opened by
GDAL's own programs. MODE:

  scatter_gpkg     scatter --out p.gpkg over St. Helens: ogrinfo's feature count is scatter's
                   count (and the CSV's lines of the same run), its CRS the DEM's (gdalsrsinfo
                   gives both the same PROJ string), the fields species, variant, scale, yaw,
                   height and rank, the points inside the DEM
  scatter_geojson  the same as GeoJSON: same count, same CRS (by its EPSG code)
  scatter_wgs84    --crs wgs84: WGS 84 longitude and latitude around the DEM's centre
  build            [exports] gis = true: DIR/plants.gpkg holds the build's count in the DEM's CRS;
                   DIR/cover.tif opens in gdalinfo in the DEM's CRS on its grid, covers the plants'
                   extent to within a cell, and its cells times the cell area sum to the count
  bad_extension    scatter --out p.shp: exit 1, one line naming the file and the extensions
                   expected, no file (nor temporary) left
  needs_dem        scatter --out p.gpkg over a plane: refused naming the file and --dem, no file
  scene_needs_dem  a scene with [exports] gis = true on flat ground: refused at its key's line,
                   no folder
  mask_polygons    [masks] polygons = a concave WGS 84 GeoJSON polygon with a hole, sown over
                   [tiles] area_latlon around it: plants.gpkg holds the build's count (over
                   100,000) in the DEM's CRS, and OGR's own point-in-polygon (SpatiaLite's
                   ST_Within in ogrinfo's SQLite dialect, the polygon reprojected by ogr2ogr) finds
                   0 of them outside
  area_latlon      [tiles] area_latlon alone, plants.gpkg in WGS 84: every point's longitude and
                   latitude inside the rectangle, and the field reaches within a tile of each edge
  mask_raster      [masks] raster = that polygon burnt by gdal_rasterize into a WGS 84 GeoTIFF,
                   and the same GeoTIFF warped beforehand by gdalwarp (-r near -et 0) onto the
                   UTM DEM's grid: both builds plant the same points (ogr2ogr's CSV of both layers
                   is the same text)
  mask_bad         refusals, each one line naming the file and the key, exit 1, no folder: a
                   missing raster, a raster without georeference, a missing polygon file, a layer
                   of points, area_latlon out of range, reversed, not finite or off the DEM
"""
import json
import os
import re
import shutil
import subprocess
import sys

wangscape, scratch, mode, source = sys.argv[1:5]
DEM = os.path.join(source, "data", "SainteHelens.dem")


def fail(message):
    sys.exit(f"gis_check {mode}: {message}")


def run(args, code=0):
    done = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if done.returncode != code:
        fail(f"{' '.join(args)}: exit {done.returncode}, expected {code}\n{done.stdout}{done.stderr}")
    return done


def ogrinfo(path):
    """Feature count, extent (x0, y0, x1, y1), the layer's WKT and field lines of `ogrinfo -so -al`."""
    text = run(["ogrinfo", "-so", "-al", path]).stdout
    count = re.search(r"^Feature Count: (\d+)$", text, re.M)
    extent = re.search(r"^Extent: \(([-\d.e+]+), ([-\d.e+]+)\) - \(([-\d.e+]+), ([-\d.e+]+)\)$", text, re.M)
    wkt = re.search(r"^Layer SRS WKT:\n(.*?)\n(?:Data axis|FID Column|Geometry Column|\w+: )", text, re.M | re.S)
    fields = dict(re.findall(r"^(\w+): (String|Integer|Real|Integer64) ", text, re.M))
    if not count or not extent or not wkt:
        fail(f"ogrinfo {path} gave no count, extent or CRS:\n{text}")
    return int(count.group(1)), [float(v) for v in extent.groups()], wkt.group(1), fields


def proj_string(path):
    return run(["gdalsrsinfo", "-o", "proj4", path]).stdout.strip().strip("'")


def check_fields(fields, path):
    expected = {"species": "String", "variant": "Integer", "scale": "Real", "yaw": "Real", "height": "Real",
                "rank": "Real"}
    if fields != expected:
        fail(f"{path}: fields {fields}, expected {expected}")


def dem_box():
    info = json.loads(run(["gdalinfo", "-json", DEM]).stdout)
    t, (w, h) = info["geoTransform"], info["size"]
    return t, w, h, (t[0], t[3] + h * t[5], t[0] + w * t[1], t[3])


def scatter(out, *extra, code=0):
    tiles = os.path.join(scratch, "tiles.json")
    if not os.path.exists(tiles):
        run([wangscape, "--quiet", "tileset", "--set", "cohen8", "--per-tile", "20", "--out", tiles])
    done = run([wangscape, "scatter", "--tileset", tiles, "--dem", DEM, "--tile-size", "16", "--max-height", "800",
                "--out", out, *extra], code)
    if code != 0:
        return done, None
    found = re.search(r"wrote .*\((\d+) instances from", done.stderr)
    if not found:
        fail(f"no count in scatter's line: {done.stderr}")
    return done, int(found.group(1))


def refused(done, words, kept):
    """One line on stderr holding every word of `words`; nothing in SCRATCH but `kept`."""
    line = done.stderr.strip()
    if not all(w in line for w in words) or len(line.splitlines()) != 1:
        fail(f"message: {line!r}")
    if os.listdir(scratch) != kept:
        fail(f"left behind: {os.listdir(scratch)}")
    print(line)


def inside(box, outer, slack=0.0):
    return (box[0] >= outer[0] - slack and box[1] >= outer[1] - slack and box[2] <= outer[2] + slack and
            box[3] <= outer[3] + slack)


def dem_wkt():
    """The DEM's CRS as a WKT file, for ogr2ogr, gdalwarp and gdaltransform."""
    path = os.path.join(scratch, "dem.wkt")
    if not os.path.exists(path):
        with open(path, "w", encoding="utf-8") as f:
            f.write(run(["gdalsrsinfo", "-o", "wkt2", DEM]).stdout)
    return path


def lon_lat(points):
    """DEM CRS (x, y) -> WGS 84 (lon, lat), by gdaltransform."""
    text = "".join(f"{x!r} {y!r}\n" for x, y in points)
    done = subprocess.run(["gdaltransform", "-s_srs", dem_wkt(), "-t_srs", "EPSG:4326", "-output_xy"], input=text,
                          capture_output=True, text=True, timeout=600, check=True)
    return [tuple(float(v) for v in line.split()) for line in done.stdout.splitlines()]


def mask_polygon():
    """A concave polygon with a hole, 520 m across, on the pumice plain 5.5 km north of the DEM's
    centre: written as WGS 84 GeoJSON (mask.geojson); returns its path and its lat/lon box."""
    t, w, h, _ = dem_box()
    cx, cy = t[0] + w * t[1] / 2, t[3] + h * t[5] / 2 + 5500
    outer = [(-250, -250), (250, -200), (230, 0), (0, 20), (-20, 260), (-260, 240), (-250, -250)]
    hole = [(-100, -60), (-60, -100), (-20, -60), (-60, -20), (-100, -60)]
    rings = [lon_lat([(cx + x, cy + y) for x, y in ring]) for ring in (outer, hole)]
    path = os.path.join(scratch, "mask.geojson")
    feature = {"type": "Feature", "properties": {"name": "field"},
               "geometry": {"type": "Polygon", "coordinates": [[list(p) for p in ring] for ring in rings]}}
    with open(path, "w", encoding="utf-8") as f:
        json.dump({"type": "FeatureCollection", "features": [feature]}, f)
    lons = [p[0] for p in rings[0]]
    lats = [p[1] for p in rings[0]]
    return path, (min(lats), min(lons), max(lats), max(lons))


def mask_scene(name, tiles="", masks="", exports=""):
    """A small scene over the DEM with [camera_aware] off and [exports] gis; returns its path."""
    scene = os.path.join(scratch, name)
    with open(scene, "w", encoding="utf-8") as f:
        f.write(f"""name = "masks"
[terrain]
dem = {json.dumps(DEM)}
[tiles]
set = "cohen8"
tile_size = 4.0
points_per_tile = 20
relaxation_rounds = 0
seed = 7
{tiles}
[masks]
{masks}
[models]
variants = 1
triangle_budget = 800
[camera_aware]
enabled = false
[exports]
povray = false
gis = true
{exports}
""")
    return scene


def build_count(scene, out):
    done = run([wangscape, "build", scene, "--out", out])
    found = re.search(r"flowers: (\d+) models, (\d+) proxies", done.stderr)
    if not found:
        fail(f"no count in build's line: {done.stderr}")
    return int(found.group(1)) + int(found.group(2))


def sql(path, query):
    """The first row of an SQLite-dialect query, as ogrinfo prints its fields: {name: text}."""
    text = run(["ogrinfo", "-q", path, "-dialect", "SQLite", "-sql", query]).stdout
    return dict(re.findall(r"^\s+(\w+) \(\w+\) = (.*)$", text, re.M))


def box_text(box):
    return "[" + ", ".join(repr(v) for v in box) + "]"


shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
dem_proj = proj_string(DEM)

if mode in ("scatter_gpkg", "scatter_geojson"):
    name = "p.gpkg" if mode == "scatter_gpkg" else "p.geojson"
    path = os.path.join(scratch, name)
    _, count = scatter(path)
    got, extent, wkt, fields = ogrinfo(path)
    if got != count or count < 100000:
        fail(f"{path}: ogrinfo counts {got} points, scatter wrote {count} (expected the same, over 100,000)")
    check_fields(fields, path)
    if proj_string(path) != dem_proj:
        fail(f"{path}: CRS {proj_string(path)!r}, the DEM's is {dem_proj!r}")
    if "NAD27" not in wkt or "UTM zone 10N" not in wkt:
        fail(f"{path}: ogrinfo's CRS is not NAD27 / UTM zone 10N:\n{wkt}")
    if not inside(extent, dem_box()[3]):
        fail(f"{path}: extent {extent} is not inside the DEM's {dem_box()[3]}")
    if mode == "scatter_gpkg":  # the same run as CSV: the same count
        csv = os.path.join(scratch, "p.csv")
        scatter(csv)
        with open(csv, encoding="utf-8") as f:
            lines = sum(1 for _ in f) - 1
        if lines != count:
            fail(f"{csv} has {lines} points, {path} {count}")
    print(f"{name}: {count} points, {dem_proj}, extent {extent}")
elif mode == "scatter_wgs84":
    path = os.path.join(scratch, "p.gpkg")
    _, count = scatter(path, "--crs", "wgs84")
    got, extent, wkt, fields = ogrinfo(path)
    check_fields(fields, path)
    if got != count or "WGS 84" not in wkt or 'ID["EPSG",4326]' not in wkt:
        fail(f"{path}: {got} points (scatter: {count}), CRS:\n{wkt}")
    if not (-122.4 < extent[0] < extent[2] < -122.0 and 46.1 < extent[1] < extent[3] < 46.4):
        fail(f"{path}: extent {extent} is not longitude, latitude around Mount St. Helens")
    print(f"{path}: {count} points, WGS 84 extent {extent}")
elif mode == "build":
    scene = os.path.join(scratch, "gis.toml")
    with open(os.path.join(source, "templates", "scenes", "small.toml"), encoding="utf-8") as f:
        text = f.read()
    text = text.replace('"../../data/SainteHelens.dem"', json.dumps(DEM))
    text = re.sub(r"^area = .*$", "area = [-300.0, 6300.0, 300.0, 6596.0]", text, flags=re.M)
    text = re.sub(r"^\[exports\]\n.*?\n\n", "[exports]\npovray = false\ngis = true\n\n", text, flags=re.M | re.S)
    with open(scene, "w", encoding="utf-8") as f:
        f.write(text)
    out = os.path.join(scratch, "field")
    done = run([wangscape, "build", scene, "--out", out])
    found = re.search(r"(\d+) flowers|flowers: (\d+) models, (\d+) proxies", done.stderr)
    if not found:
        fail(f"no count in build's line: {done.stderr}")
    count = int(found.group(1)) if found.group(1) else int(found.group(2)) + int(found.group(3))
    plants = os.path.join(out, "plants.gpkg")
    got, extent, wkt, fields = ogrinfo(plants)
    check_fields(fields, plants)
    if got != count or count < 1000:
        fail(f"{plants}: ogrinfo counts {got} points, the build {count} (expected the same, over 1,000)")
    if proj_string(plants) != dem_proj:
        fail(f"{plants}: CRS {proj_string(plants)!r}, the DEM's is {dem_proj!r}")
    cover = os.path.join(out, "cover.tif")
    info = json.loads(run(["gdalinfo", "-json", cover]).stdout)
    if proj_string(cover) != dem_proj:
        fail(f"{cover}: CRS {proj_string(cover)!r}, the DEM's is {dem_proj!r}")
    t, (w, h) = info["geoTransform"], info["size"]
    dt, _, _, _ = dem_box()
    if t[1] != dt[1] or t[5] != dt[5] or abs((t[0] - dt[0]) / t[1] % 1) > 1e-6 or abs((t[3] - dt[3]) / t[5] % 1) > 1e-6:
        fail(f"{cover}: geotransform {t} is not on the DEM's grid {dt}")
    box = (t[0], t[3] + h * t[5], t[0] + w * t[1], t[3])
    cell = abs(t[1] * t[5])
    if not inside(extent, box) or not inside(box, extent, slack=max(abs(t[1]), abs(t[5]))):
        fail(f"{cover}: extent {box} does not hold the plants' {extent} to within a cell")
    xyz = run(["gdal_translate", "-q", "-of", "XYZ", cover, "/vsistdout/"]).stdout.split()
    values = [float(v) for v in xyz[2::3]]
    total = sum(values) * cell
    if len(values) != w * h or abs(total - count) > 1e-4 * count + 0.5:
        fail(f"{cover}: {len(values)} cells summing to {total:.3f} plants, the build placed {count}")
    band = info["bands"][0]
    if band["type"] != "Float32" or band.get("description") != "plants per square metre":
        fail(f"{cover}: band {band}")
    print(f"{plants}: {count} points; {cover}: {w} x {h} cells of {cell:g} m2, sum x area {total:.3f}")
elif mode == "bad_extension":
    path = os.path.join(scratch, "p.shp")
    done, _ = scatter(path, code=1)
    refused(done, ["p.shp", ".csv", ".ply", ".gpkg", ".geojson"], ["tiles.json"])
elif mode == "needs_dem":
    tiles = os.path.join(scratch, "tiles.json")
    run([wangscape, "--quiet", "tileset", "--set", "cohen8", "--per-tile", "10", "--out", tiles])
    done = run([wangscape, "scatter", "--tileset", tiles, "--plane", "64x64", "--out",
                os.path.join(scratch, "p.gpkg")], 1)
    refused(done, ["p.gpkg", "--dem"], ["tiles.json"])
elif mode == "scene_needs_dem":
    scene = os.path.join(scratch, "flat.toml")
    with open(scene, "w", encoding="utf-8") as f:
        f.write("[exports]\npovray = false\ngis = true\n")
    done = run([wangscape, "build", scene, "--out", os.path.join(scratch, "flat")], 1)
    refused(done, ["flat.toml:3: 'exports.gis' needs [terrain] dem"], ["flat.toml"])
elif mode == "mask_polygons":
    polygon, (lat0, lon0, lat1, lon1) = mask_polygon()
    margin = 0.0005  # degrees: the sown rectangle reaches beyond the polygon on every side
    area = box_text((lat0 - margin, lon0 - margin, lat1 + margin, lon1 + margin))
    scene = mask_scene("masks.toml", tiles=f"area_latlon = {area}", masks='polygons = "mask.geojson"')
    out = os.path.join(scratch, "field")
    count = build_count(scene, out)
    plants = os.path.join(out, "plants.gpkg")
    got, extent, wkt, fields = ogrinfo(plants)
    if got != count or count < 100000:
        fail(f"{plants}: ogrinfo counts {got} points, the build {count} (expected the same, over 100,000)")
    if proj_string(plants) != dem_proj:
        fail(f"{plants}: CRS {proj_string(plants)!r}, the DEM's is {dem_proj!r}")
    # The polygon reprojected by OGR into the DEM's CRS beside a copy of the points.
    check = os.path.join(scratch, "check.gpkg")
    shutil.copyfile(plants, check)
    run(["ogr2ogr", "-update", "-t_srs", dem_wkt(), "-nln", "mask", check, polygon])
    row = sql(check, "SELECT SUM(ST_Within(p.geom, m.geom)) AS inside, SUM(NOT ST_Within(p.geom, m.geom)) AS outside "
                     "FROM plants p, mask m")
    if row.get("outside") != "0" or row.get("inside") != str(count):
        fail(f"OGR's point-in-polygon: {row} of {count} plants (expected all inside, 0 outside)")
    print(f"{plants}: {count} points, OGR's ST_Within: {row['inside']} inside, {row['outside']} outside; {dem_proj}")
elif mode == "area_latlon":
    _, (lat0, lon0, lat1, lon1) = mask_polygon()
    box = (lat0, lon0, lat1, lon1)
    scene = mask_scene("area.toml", tiles=f"area_latlon = {box_text(box)}", exports='gis_crs = "wgs84"')
    out = os.path.join(scratch, "field")
    count = build_count(scene, out)
    plants = os.path.join(out, "plants.gpkg")
    row = sql(plants, "SELECT COUNT(*) AS n, MIN(ST_X(geom)) AS lon0, MIN(ST_Y(geom)) AS lat0, "
                      "MAX(ST_X(geom)) AS lon1, MAX(ST_Y(geom)) AS lat1 FROM plants")
    got = (float(row["lat0"]), float(row["lon0"]), float(row["lat1"]), float(row["lon1"]))
    tile = 4.0 / 111000 * 2  # degrees: two tiles of latitude (and more than two of longitude)
    if int(row["n"]) != count or count < 100000:
        fail(f"{plants}: {row['n']} points, the build {count} (expected the same, over 100,000)")
    if not (got[0] >= box[0] and got[1] >= box[1] and got[2] <= box[2] and got[3] <= box[3]):
        fail(f"{plants}: points span {got}, outside area_latlon {box}")
    if max(abs(g - b) for g, b in zip(got, box)) > tile:
        fail(f"{plants}: points span {got}, not to within two tiles of area_latlon {box}")
    print(f"{plants}: {count} points spanning {got} inside area_latlon {box}")
elif mode == "mask_raster":
    polygon, (lat0, lon0, lat1, lon1) = mask_polygon()
    margin = 0.003
    te = [lon0 - margin, lat0 - margin, lon1 + margin, lat1 + margin]
    wgs84 = os.path.join(scratch, "mask_wgs84.tif")
    run(["gdal_rasterize", "-q", "-burn", "1", "-ot", "Byte", "-tr", "0.001", "0.001", "-te", *map(repr, te), polygon,
         wgs84])
    t, w, h, (x0, y0, x1, y1) = dem_box()
    warped = os.path.join(scratch, "mask_dem.tif")
    run(["gdalwarp", "-q", "-r", "near", "-et", "0", "-t_srs", dem_wkt(), "-te", *map(repr, (x0, y0, x1, y1)), "-ts",
         str(w), str(h), wgs84, warped])
    area = box_text((lat0 - margin, lon0 - margin, lat1 + margin, lon1 + margin))
    layers = []
    for name in ("mask_wgs84.tif", "mask_dem.tif"):
        scene = mask_scene(name + ".toml", tiles=f"area_latlon = {area}", masks=f"raster = {json.dumps(name)}")
        out = os.path.join(scratch, name + ".field")
        count = build_count(scene, out)
        text = run(["ogr2ogr", "-f", "CSV", "/vsistdout/", os.path.join(out, "plants.gpkg"), "-lco",
                    "GEOMETRY=AS_XY"]).stdout
        layers.append((name, count, text))
    (a, count_a, text_a), (b, count_b, text_b) = layers
    if count_a != count_b or text_a != text_b or count_a < 1000:
        fail(f"{a}: {count_a} plants, {b} (warped by gdalwarp): {count_b}; the same points: {text_a == text_b}")
    print(f"{a} and {b} (gdalwarp -r near -et 0): the same {count_a} plants")
elif mode == "mask_bad":
    polygon, (lat0, lon0, lat1, lon1) = mask_polygon()
    area = box_text((lat0, lon0, lat1, lon1))
    points = os.path.join(scratch, "points.geojson")
    with open(points, "w", encoding="utf-8") as f:
        f.write('{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, '
                f'"geometry": {{"type": "Point", "coordinates": [{lon0}, {lat0}]}}}}]}}')
    run(["gdal_create", "-q", "-of", "GTiff", "-outsize", "8", "8", "-bands", "1", "-burn", "1",
         os.path.join(scratch, "nogeo.tif")])
    cases = [
        ("missing_raster", "", 'raster = "missing.tif"',
         ["missing.tif", "'masks.raster'", "does not exist", "georeferenced raster"]),
        ("nogeo", "", 'raster = "nogeo.tif"', ["nogeo.tif", "'masks.raster'", "no georeference", "GeoTIFF"]),
        ("missing_polygons", "", 'polygons = "missing.gpkg"',
         ["missing.gpkg", "'masks.polygons'", "does not exist", "polygons"]),
        ("points", "", 'polygons = "points.geojson"',
         ["points.geojson", "'masks.polygons'", "Point", "expected polygons"]),
        ("latitude", "area_latlon = [95.0, -122.2, 96.0, -122.1]", "",
         ["mask_bad_latitude.toml:", "'tiles.area_latlon'", "latitudes in [-90, 90]"]),
        ("reversed", f"area_latlon = [{lat1}, {lon0}, {lat0}, {lon1}]", "",
         ["mask_bad_reversed.toml:", "'tiles.area_latlon'", "max > min"]),
        ("nan", "area_latlon = [nan, -122.2, 46.3, -122.1]", "",
         ["mask_bad_nan.toml:", "'tiles.area_latlon'", "finite"]),
        ("inf", "area_latlon = [46.2, -inf, 46.3, -122.1]", "",
         ["mask_bad_inf.toml:", "'tiles.area_latlon'", "finite"]),
        ("elsewhere", "area_latlon = [40.0, -100.0, 40.1, -99.9]", "",
         ["'tiles.area_latlon' misses DEM", "SainteHelens.dem", "expected a latitude/longitude rectangle"]),
    ]
    for name, tiles, masks, words in cases:
        scene = mask_scene(f"mask_bad_{name}.toml", tiles=tiles or f"area_latlon = {area}", masks=masks)
        out = os.path.join(scratch, name)
        done = run([wangscape, "build", scene, "--out", out], 1)
        line = done.stderr.strip()
        if not all(word in line for word in words) or len(line.splitlines()) != 1:
            fail(f"{name}: message {line!r}, expected one line with {words}")
        left = [f for f in os.listdir(scratch) if f.startswith(".")]  # a staging folder is ".NAME..."
        if os.path.exists(out) or left:
            fail(f"{name}: left behind {left or out}")
        print(line)
else:
    fail("unknown mode")
