#!/usr/bin/env python3
"""Every scene-file key a message, help text or document hints at ("[exports] blender = true")
names a section and key as the file spells them: the section is one of docs/scene-file.md's,
and the key is in that section's table (issue 40: a hint named [export], which the reader refuses).

usage: key_hints.py SOURCE_DIR; exit 1 listing each hint that names no such key."""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
doc = (root / "docs/scene-file.md").read_text(encoding="utf-8")

# docs/scene-file.md: "## `[section]`" (or "## `[[species]]`") and its rows "| `key`, `key2` | ...".
keys = {}
section = None
for line in doc.splitlines():
    heading = re.match(r"^##+ `\[{1,2}([a-z_.]+)\]{1,2}`", line)
    if heading:
        section = heading.group(1)
        keys.setdefault(section, set())
        continue
    if section and line.startswith("| `"):
        first_cell = line.split("|")[1]
        keys[section].update(re.findall(r"`([a-z_]+)`", first_cell))

hint = re.compile(r"\[\[?([a-z_.]+)\]\]? ([a-z_]+) ?=")
sources = [p for folder in ("cli", "core", "exporters", "folder", "generator", "renders", "scene", "terrain", "templates", "docs")
           for p in (root / folder).rglob("*") if p.suffix in (".cpp", ".h", ".md", ".py", ".toml")]
sources.append(root / "README.md")
wrong, checked = [], 0
for path in sources:
    for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
        for match in hint.finditer(line):
            name, key = match.groups()
            checked += 1
            if name not in keys:
                wrong.append(f"{path.relative_to(root)}:{number}: [{name}] is no section of docs/scene-file.md")
            elif key not in keys[name]:
                wrong.append(f"{path.relative_to(root)}:{number}: [{name}] has no key '{key}' in docs/scene-file.md")
if len(keys) < 5 or checked == 0:
    sys.exit(f"key_hints.py: read {len(keys)} sections and {checked} hints; expected the scene file's sections and some hints")
print(f"{checked} hints of {len(keys)} sections checked")
if wrong:
    print("\n".join(wrong))
    sys.exit(1)
