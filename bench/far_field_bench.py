#!/usr/bin/env python3
"""bench/far_field_bench.py [WANGSCAPE]: the painted far field of the whole-DEM still
(templates/scenes/whole-dem.toml) against the same field with proxies to FAR_REF meters.

Builds three folders (as the scene is; far_texture = false; far = FAR_REF), renders them with
POV-Ray, and finds the far band: a bake that is magenta where the scene's bake is painted and
the reference's is not, rendered through the scene's folder (its flowers in front hide what
they hide). Prints, for the band, the mean sRGB color and the share of sunflower-yellow pixels
(tests/renders/povray_render_test.cpp's test) of the painted still and of the reference, and
the timings. Needs povray and oiiotool; pure Python otherwise. Note the load (printed).
  python3 bench/far_field_bench.py                 # FAR_REF=2500
"""
import os, shutil, subprocess, sys, tempfile, time

src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = sys.argv[1] if len(sys.argv) > 1 else os.path.join(src, "build/release/cli/wangscape")
far_ref = os.environ.get("FAR_REF", "2500")


def read(path):  # (width, height, RGB bytes) through oiiotool's binary PPM
    with tempfile.TemporaryDirectory() as d:
        ppm = os.path.join(d, "x.ppm")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint8", "-o", ppm], check=True)
        data = open(ppm, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    return w, h, parts[3]


def write(path, w, h, pixels):
    with tempfile.TemporaryDirectory() as d:
        ppm = os.path.join(d, "x.ppm")
        open(ppm, "wb").write(b"P6\n%d %d\n255\n" % (w, h) + bytes(pixels))
        subprocess.run(["oiiotool", ppm, "-o", path], check=True)


def build(scene, out):
    t = time.time()
    subprocess.run([binary, "build", scene, "--out", out], check=True, stderr=subprocess.DEVNULL)
    return time.time() - t


def render(folder):
    t = time.time()
    subprocess.run(["povray", "scene.ini", "-D"], cwd=folder, check=True, capture_output=True)
    return time.time() - t


def yellow(r, g, b):
    return r > 0.45 and g > 0.28 and b < 0.5 * g and r > 1.2 * b + 0.25


def main():
    print(subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    work = tempfile.mkdtemp()
    try:
        text = open(os.path.join(src, "templates/scenes/whole-dem.toml")).read()
        text = text.replace('"../../data/SainteHelens.dem"', '"%s"' % os.path.join(src, "data/SainteHelens.dem"))
        scenes = {"painted": text,
                  "unpainted": text.replace("proxy_triangles = ", "far_texture = false\nproxy_triangles = "),
                  "reference": text.replace("proxy_triangles = ", "far = %s.0\nproxy_triangles = " % far_ref)}
        for name, body in scenes.items():
            path = os.path.join(work, name + ".toml")
            open(path, "w").write(body)
            seconds = build(path, os.path.join(work, name))
            print("%s: build %.1f s, POV-Ray %.1f s" % (name, seconds, render(os.path.join(work, name))))
        w, h, painted = read(os.path.join(work, "painted/ground.png"))
        _, _, plain = read(os.path.join(work, "unpainted/ground.png"))
        _, _, ref = read(os.path.join(work, "reference/ground.png"))
        marked = bytearray(plain)
        for k in range(0, len(plain), 3):
            if painted[k:k + 3] != plain[k:k + 3] and ref[k:k + 3] == plain[k:k + 3]:
                marked[k:k + 3] = b"\xff\x00\xff"
        band_dir = os.path.join(work, "band")
        shutil.copytree(os.path.join(work, "painted"), band_dir)
        write(os.path.join(band_dir, "ground.png"), w, h, marked)
        ini = open(os.path.join(band_dir, "scene.ini")).read().replace(os.path.join(work, "painted"), band_dir)
        open(os.path.join(band_dir, "scene.ini"), "w").write(ini)
        render(band_dir)
        w, h, m = read(os.path.join(band_dir, "render.png"))
        band = [m[k] > 2 * m[k + 1] + 40 and m[k + 2] > 2 * m[k + 1] + 40 for k in range(0, len(m), 3)]
        print("far band: %d of %d pixels (the ground painted beyond far, short of %s m)" % (sum(band), w * h, far_ref))
        for name in ("painted", "reference"):
            _, _, p = read(os.path.join(work, name, "render.png"))
            s, n, y = [0.0, 0.0, 0.0], 0, 0
            for i in range(w * h):
                if not band[i]:
                    continue
                r, g, b = p[3 * i] / 255, p[3 * i + 1] / 255, p[3 * i + 2] / 255
                s[0] += r; s[1] += g; s[2] += b; n += 1; y += yellow(r, g, b)
            print("%-9s far band mean sRGB (%.3f, %.3f, %.3f), sunflower-yellow %.1f %%" %
                  (name, s[0] / n, s[1] / n, s[2] / n, 100 * y / n))
    finally:
        shutil.rmtree(work)
    print(subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


main()
