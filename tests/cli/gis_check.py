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
else:
    fail("unknown mode")
