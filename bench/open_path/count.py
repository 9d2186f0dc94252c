#!/usr/bin/env python3
"""Files visited and climbs back on the viewer's path, from the traces trace_hook.c writes.

count.py BINARY BASE SOURCE_DIR TRACE... [--list]

The method, exactly (bench/open_path/README.md says why):
- The path: the project functions run inside the window on the viewer's thread (the trace is
  taken with --threads 1, so TBB runs every task there and the order is the same every run),
  each once, at its first entry, attached to the function that first called it.
  Compiler-generated members (a constructor, destructor or assignment whose source line is the
  class's own `struct`/`class` line or `= default`) are left out: there is nothing to read.
- A function's file: where its definition is (llvm-symbolizer). Files are counted as sources
  (.cpp), headers (.h) and together; a unit is a header with its source (scene/scene.h and
  scene/scene.cpp are one unit).
- A climb: a call of the path from a function in unit A into a function in another unit B
  (the first call of B's function) where B's layer is above A's ("up": a callback, a hook), or
  B's layer is not above A's but the path entered B before and has left it (B is not A's unit
  nor the unit of any caller above A on the stack: "back", the reader returns to a file already
  read). Climbs are counted once per (A, B) pair of units: a reader who goes back from A to B
  for three helpers makes one trip. Calls inside a unit are free. Layers: docs/architecture.md,
  lowest first (LAYERS below).
"""
import json
import os
import re
import shutil
import subprocess
import sys

LAYERS = [
    ("core/", 0),
    ("generator/", 1), ("terrain/", 1), ("templates/", 1),
    ("scene/", 2),
    ("exporters/", 3),
    ("folder/", 4),
    ("renders/trace/", 5),
    ("renders/ldi/", 6), ("renders/external/", 6),
    ("renders/view/", 7),
    ("renders/window/", 8), ("renders/batch/", 8),
    ("renders/", 9),
    ("cli/", 10),
]


def layer(path):
    for prefix, rank in LAYERS:
        if path.startswith(prefix):
            return rank
    raise SystemExit(f"count.py: no layer for {path}")


def unit(path):
    return os.path.splitext(path)[0]


def resolve(binary, base, source, offsets):
    """offset -> (function, project-relative file, line). llvm-symbolizer, not addr2line: binutils'
    addr2line names the unity-build file instead of the source for some functions (DWARF 5)."""
    offsets = sorted(offsets)
    tool = shutil.which("llvm-symbolizer") or shutil.which("llvm-symbolizer-14")
    text = "\n".join(hex(o + base) for o in offsets) + "\n"
    answers = subprocess.run([tool, "--output-style=JSON", "--demangle", "--no-inlines", "-e", binary], input=text,
                             capture_output=True, text=True, check=True).stdout.splitlines()
    table = {}
    for o, answer in zip(offsets, answers):
        symbol = json.loads(answer)["Symbol"][0]
        where = os.path.normpath(symbol["FileName"])
        if where.startswith(source + "/"):
            where = where[len(source) + 1:]
        else:  # an object ccache compiled in another worktree (base_dir, hash_dir off) names its file there
            where = in_tree(source, where)
        table[o] = (symbol["FunctionName"], where, symbol["Line"])
    return table


TOP = ("core", "generator", "terrain", "templates", "scene", "exporters", "folder", "renders", "cli", "bench")


def in_tree(source, path):
    """The project's part of a path from another checkout: from the first top folder on that names
    a file of this one."""
    parts = path.split("/")
    for k, part in enumerate(parts[:-1]):
        rest = "/".join(parts[k:])
        if part in TOP and os.path.isfile(os.path.join(source, rest)):
            return rest
    return path


SPECIAL = re.compile(r"(?:^|::)(~?)(\w+)::(?:~?\2|operator=)\(")
_lines = {}


def generated(source, name, file, line):
    """A constructor, destructor or assignment the compiler wrote (or `= default`)."""
    if not SPECIAL.search(name.split("(")[0] + "("):
        return False
    path = os.path.join(source, file)
    if path not in _lines:
        with open(path, errors="replace") as f:
            _lines[path] = f.read().splitlines()
    text = _lines[path][line - 1] if 0 < line <= len(_lines[path]) else ""
    return bool(re.match(r"\s*(struct|class)\b", text)) or "= default" in text


def analyse(binary, base, source, trace, show):
    records = []
    with open(trace) as f:
        for line in f:
            _, seq, thread, fn, *stack = line.split()
            stack = [int(a, 16) for a in stack[0].split(",")] if stack else []
            records.append((int(seq), int(thread), int(fn, 16), stack))
    records.sort()
    table = resolve(binary, base, source, {r[2] for r in records} | {a for r in records for a in r[3]})
    # The viewer's thread only (with --threads 1, every call of the path): the thread that entered
    # the window's first function. Others (the run's signal watcher, started in main) are not the path.
    records = [r for r in records if r[1] == records[0][1]]
    kept = [r for r in records if not generated(source, *table[r[2]])]
    skipped = len(records) - len(kept)
    in_tree = {r[2] for r in kept}
    files, seen_units, climbs = [], set(), []
    for _, thread, fn, stack in kept:
        name, file, _ = table[fn]
        if file not in files:
            files.append(file)
        # The caller: the nearest function on the stack that is in the tree (a compiler-generated
        # member or a function first run before the window is passed over).
        callers = [a for a in stack if a in in_tree]
        if callers:
            caller_name, caller, _ = table[callers[-1]]
            ancestors = {unit(table[a][1]) for a in callers}
            if unit(caller) != unit(file):
                if layer(file) > layer(caller):
                    climbs.append(("up", caller, caller_name, file, name))
                elif unit(file) in seen_units and unit(file) not in ancestors:
                    climbs.append(("back", caller, caller_name, file, name))
        seen_units.add(unit(file))
    headers = [f for f in files if f.endswith((".h", ".hpp"))]
    pairs = {}  # (caller's unit, callee's unit) -> the first climb between them
    for c in climbs:
        pairs.setdefault((unit(c[1]), unit(c[3])), c)
    up = sum(c[0] == "up" for c in pairs.values())
    into_core = sum(c[3].startswith("core/") for c in pairs.values())
    print(f"{os.path.basename(trace)}: {len(kept)} functions ({skipped} compiler-generated left out; "
          "one thread); "
          f"files {len(files)} ({len(files) - len(headers)} sources + {len(headers)} headers; {len(seen_units)} units); "
          f"climbs {len(pairs)} ({up} up, {len(pairs) - up} back; {into_core} of them into core/; "
          f"{len(climbs)} calls)")
    if show:
        for f in files:
            print(f"  file   L{layer(f):<2} {f}")
        for kind, caller, caller_name, file, name in pairs.values():
            print(f"  {kind:5}  {caller} {caller_name.split('(')[0]}\n         -> {file} {name.split('(')[0]}")


def main():
    args = [a for a in sys.argv[1:] if a != "--list"]
    binary, base, source = args[0], int(args[1], 16), os.path.normpath(os.path.abspath(args[2]))
    for trace in args[3:]:
        analyse(binary, base, source, trace, "--list" in sys.argv)


if __name__ == "__main__":
    main()
