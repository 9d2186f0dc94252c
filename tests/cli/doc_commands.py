#!/usr/bin/python3
"""Every `wangscape ...` command in the docs runs (issue 40).

Reads the fenced ```sh blocks of README.md and docs/*.md and runs their lines in order, one
scratch folder per file, so that a sequence (`demo --print-scene > field.toml`, `build`, then
`render`) runs as a user would type it. `wangscape` is the built binary (first on PATH); `data`
and `templates` in the scratch folder lead to the source tree's. Inputs are made small where the
docs' would take minutes: the default scene printed by `demo --print-scene` is cut to a 24 x 36 m
patch at 160 x 90 pixels (shrink_scene), frame and preview sizes are lowered, `--stats` repeats
2 frames and `--compare` takes 4 samples of truth (REWRITES); a file that uses `field`, `field.toml`
or `path.json` without making them gets small ones first (SETUP). Commands too long to run, or that
need a window, a cluster or a human, are in SKIP with the reason.

Fails when a command exits non-zero, when a line in a fence that is not marked sh starts with
`wangscape` (mark it ```sh so that it runs), or when a SKIP entry matches no command in the docs
(a stale entry). Usage: doc_commands.py --bin BIN --source DIR --scratch DIR [--only FILE] [--list]
"""
import argparse
import glob
import os
import re
import resource
import shutil
import subprocess
import sys
import time

# Commands not run, each with why. Keyed by the command as written (its comment cut off); a key
# that names a file ("README.md: ...") holds for that file only.
SKIP = {
    "wangscape view field":
        "opens an interactive window and waits for the user; the scripted window runs below (xvfb-run) and in tests/cli/view.cmake",
    "wangscape batch run valley.toml --out valley":
        "renders the batch's 4 stills of the full default scene with POV-Ray (minutes); tests/cli/batch.cmake runs small batches",
    "wangscape batch run valley.toml --out valley --executor slurm --chunk 4 --throttle 8":
        "needs a Slurm cluster and renders the full default scene; tests/cli/batch.cmake runs the Slurm executor on a small batch",
    "wangscape batch run valley.toml --out valley --executor slurm":
        "needs a Slurm cluster and renders the full default scene; tests/cli/batch.cmake runs the Slurm executor on a small batch",
    "wangscape batch status valley":
        "reads the folder of `batch run`, which is not run here (above); tests/cli/batch.cmake checks status",
    "wangscape demo --scene meadow --out meadow":
        "builds and renders the full meadow scene (86,637 plants, 11 s idle, about a minute under load) at full size; tests/cli/povray.cmake runs the meadow demo",
    "wangscape render whole-dem":
        "renders 24,740 proxies over the whole DEM with POV-Ray at 640 x 360 (minutes); the build before it runs",
    "wangscape scatter --tileset tiles.json --dem data/SainteHelens.dem --tile-size 8 --max-height 800 --out points.gpkg":
        "writes a 106 MB GeoPackage in 12 s of CPU; tests/cli/gis.cmake writes GeoPackages of small fields",
    "scripts/one_look_picture.sh build/release/cli/wangscape ferns.png templates/scenes/card-plants.toml":
        "makes the README's picture (the scene in three engines at 320 x 180 and its band table); tests/cli/look.cmake runs the same table on the small scene",
    "docs/texture-tiles.md: wangscape noise tiles --set corner-3 --lattice 32 --octaves 3 --out noise [--preview 1024x512 noise.png] [--pattern marble]":
        "a synopsis ([...] marks optional parts); README.md runs the same command",
    "docs/texture-tiles.md: wangscape texture tiles --exemplar meadow [--exemplar2 pumice.png] --set corner-2 --size 64 --out tex [--preview 1024x512 tex.png]":
        "a synopsis ([...] marks optional parts); README.md runs the same command",
}

# Smaller sizes for every command that is run: (pattern, replacement, applies when the command
# matches this too). The docs' sizes are for a user's eyes; the test needs only that it runs.
REWRITES = [
    (r"--size \d+x\d+", "--size 160x90", r"^wangscape view|--script"),
    (r"--preview \d+x\d+", "--preview 256x128", r""),
    (r"--width 320\b", "--width 64", r"--path"),
    (r"$", " --repeat 2", r"^wangscape view (?!.*--repeat)(?!.*--path).*--stats"),
    (r"$", " --truth-spp 4", r"^wangscape view (?!.*--truth-spp).*--compare"),
    (r"$", " --size 160x90", r"--script(?!.*--size)"),
    (r"$", " --width 96", r"render \S+ --engine blender$"),  # Cycles at the scene's 480 x 270: a minute under load
]

# The small stand-in of the default scene: its keys as `demo --print-scene` prints them, each
# value cut down (the [exports] lines stay, so the docs' sed lines still find them).
SHRINK = [
    (r"^area = .*$", "area = [-12.0, 6560.0, 12.0, 6596.0]"),
    (r"^points_per_tile = .*$", "points_per_tile = 10"),
    (r"^relaxation_rounds = .*$", "relaxation_rounds = 0"),
    (r"^variants = .*$", "variants = 3"),
    (r"^triangle_budget = .*$", "triangle_budget = 800"),
    (r"^width = .*$", "width = 160"),
    (r"^height = .*$", "height = 90"),
    (r"^antialias = .*$", "antialias = 1"),
    (r"^bake_pixels = .*$", "bake_pixels = 256"),
]
LDI_SECTION = "\n[ldi]\nlevels = 4\ndirections = 2\nsky_rays = 0\n"  # 2 levels: 78 MB of steep sets

PATH_JSON = """{"keyframes": [
  {"time": 0, "position": [0, 6600], "height_above_ground": 2.0, "look_at": [0, 6560], "look_at_height_above_ground": 0.5},
  {"time": 0.25, "position": [1, 6596], "height_above_ground": 2.0, "look_at": [-1, 6556], "look_at_height_above_ground": 0.5}]}
"""


def shrink_scene(path):
    text = open(path).read()
    for pattern, repl in SHRINK:
        text = re.sub(pattern, repl, text, flags=re.M)
    if not re.search(r"^\[ldi\]", text, flags=re.M):
        text += LDI_SECTION
    open(path, "w").write(text)


def fences(path):
    """Yields (fence index, line number, fence language, line) for every line inside a ``` fence."""
    lang, index = None, 0
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        m = re.match(r"^\s*```\s*(\S*)", line)
        if m:
            lang = None if lang is not None else m.group(1)
            index += 1
            continue
        if lang is not None:
            yield index, number, lang, line.rstrip("\n")


def strip_comment(line):
    """The command without its trailing `# ...` (a # inside quotes stays)."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1] in " \t"):
            return line[:i].rstrip()
    return line.rstrip()


def doc_files(source):
    return ["README.md"] + sorted(os.path.relpath(p, source) for p in glob.glob(os.path.join(source, "docs", "*.md")))


def commands_of(source, rel, errors):
    """The lines to run of one file: (line number, command, is a wangscape command)."""
    blocks, last = [], None
    for index, number, lang, line in fences(os.path.join(source, rel)):
        command = strip_comment(line).strip()
        if not command:
            continue
        if lang not in ("sh", "bash", "shell", "console"):
            if command.startswith("wangscape "):
                errors.append(f"{rel}:{number}: a wangscape command in a ```{lang} fence: mark it ```sh so that this test runs it")
            continue
        if index != last:
            blocks.append([])
        blocks[-1].append((number, command, re.search(r"(^|\s)wangscape\s", command) is not None))
        last = index
    # The other lines (sed ...) run where they stand among wangscape commands; a block without
    # any (building, fuzzing) is not this test's.
    return [c for block in blocks if any(w for _, _, w in block) for c in block]


def skip_reason(rel, command):
    return SKIP.get(f"{rel}: {command}") or SKIP.get(command)


def rewrite(command):
    for pattern, repl, when in REWRITES:
        if re.search(when, command):
            command = re.sub(pattern, repl, command, count=1)
    return command


def setup(rel, commands, work, source, binary):
    """Small stand-ins for what a file uses without making it."""
    with open(os.path.join(work, "path.json"), "w") as f:
        f.write(PATH_JSON)
    makes_field = any(re.search(r"> *field\.toml|--out field(\s|$)", c) for _, c, _ in commands)
    uses_field = any(re.search(r"\bfield(\.toml)?(\s|$)", c) for _, c, _ in commands)
    if uses_field and not makes_field:
        env = run_env(work, binary)
        subprocess.run(["wangscape", "demo", "--print-scene"], cwd=work, env=env, check=True,
                       stdout=open(os.path.join(work, "field.toml"), "w"))
        shrink_scene(os.path.join(work, "field.toml"))
        subprocess.run(["wangscape", "--quiet", "build", "field.toml", "--out", "field"], cwd=work, env=env, check=True)


def run_env(work, binary):
    env = dict(os.environ)
    bindir = os.path.join(work, ".bin")
    env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    return env


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--scratch", required=True)
    ap.add_argument("--only", help="one file, e.g. README.md")
    ap.add_argument("--list", action="store_true", help="list the commands and what is done with each")
    args = ap.parse_args()
    source = os.path.abspath(args.source)
    binary = os.path.abspath(args.bin)

    errors, failures = [], []
    files = doc_files(source)
    per_file = {rel: commands_of(source, rel, errors) for rel in files}
    used_skips = set()
    for rel, commands in per_file.items():
        for _, command, _ in commands:
            if f"{rel}: {command}" in SKIP:
                used_skips.add(f"{rel}: {command}")
            elif command in SKIP:
                used_skips.add(command)
    for key in SKIP:
        if key not in used_skips:
            errors.append(f"SKIP lists a command no doc holds (remove it, or fix it to the docs' text): {key}")

    ran = skipped = 0
    start, cpu_start = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    for rel in files:
        if args.only and rel != args.only:
            continue
        commands = per_file[rel]
        if not any(is_ws for _, _, is_ws in commands):
            continue
        work = os.path.join(os.path.abspath(args.scratch), rel.replace("/", "_").replace(".md", ""))
        if not args.list:
            shutil.rmtree(work, ignore_errors=True)
            os.makedirs(os.path.join(work, ".bin"))
            os.symlink(binary, os.path.join(work, ".bin", "wangscape"))
            for name in ("data", "templates"):
                os.symlink(os.path.join(source, name), os.path.join(work, name))
            setup(rel, commands, work, source, binary)
        for number, command, is_ws in commands:
            reason = skip_reason(rel, command)
            if reason:
                skipped += 1
                print(f"skip {rel}:{number}: {command}\n     ({reason})", flush=True)
                continue
            actual = rewrite(command) if is_ws else command
            shown = command if actual == command else f"{command}\n     as: {actual}"
            if args.list:
                print(f"run  {rel}:{number}: {shown}")
                ran += is_ws
                continue
            t0, cpu0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
            p = subprocess.run(["bash", "-c", "set -o pipefail; " + actual], cwd=work, env=run_env(work, binary),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
            took = time.monotonic() - t0
            cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = cpu1.ru_utime + cpu1.ru_stime - cpu0.ru_utime - cpu0.ru_stime
            ran += is_ws
            status = "ok  " if p.returncode == 0 else "FAIL"
            print(f"{status} {rel}:{number}: {shown}  ({took:.1f} s, {cpu:.1f} s of CPU)", flush=True)
            if p.returncode != 0:
                tail = p.stdout.decode(errors="replace").strip().splitlines()[-8:]
                print("     " + "\n     ".join(tail), flush=True)
                failures.append(f"{rel}:{number}: {command} (exit {p.returncode})")
            elif re.search(r"> *field\.toml\s*$", actual) and "--print-scene" in actual:
                shrink_scene(os.path.join(work, "field.toml"))

    cpu_end = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = cpu_end.ru_utime + cpu_end.ru_stime - cpu_start.ru_utime - cpu_start.ru_stime
    print(f"\n{ran} doc commands run, {skipped} skipped (listed with reasons), in {time.monotonic() - start:.0f} s"
          f" ({cpu:.0f} s of CPU)")
    for e in errors:
        print("error: " + e)
    for f in failures:
        print("failed: " + f)
    if not errors and not failures and not args.list:
        shutil.rmtree(os.path.abspath(args.scratch), ignore_errors=True)  # hundreds of MB; kept on failure
    return 1 if errors or failures else 0


if __name__ == "__main__":
    sys.exit(main())
