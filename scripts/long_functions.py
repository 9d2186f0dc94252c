#!/usr/bin/env python3
"""Lists the product code's functions longer than a limit (issue 36's measure), and its files over 900 lines.

A function is counted from its signature's first line (a line at column 0 with '(' that is not a
declaration) to the closing brace at column 0, as clang-format lays them out. Usage:
  scripts/long_functions.py [ROOT] [LIMIT]   (defaults: the checkout, 120 lines)
"""
import os
import re
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
limit = int(sys.argv[2]) if len(sys.argv) > 2 else 120
folders = ["core", "generator", "terrain", "templates", "scene", "exporters", "folder", "renders", "cli"]
long_functions, long_files = [], []
for folder in folders:
    for directory, _, names in os.walk(os.path.join(root, folder)):
        for name in names:
            if not name.endswith((".cpp", ".h")):
                continue
            path = os.path.join(directory, name)
            lines = open(path, errors="replace").read().split("\n")
            relative = os.path.relpath(path, root)
            if len(lines) > 900:
                long_files.append((len(lines), relative))
            i = 0
            while i < len(lines):
                line = lines[i]
                starts = (re.match(r"^[A-Za-z]", line) and "(" in line and not line.rstrip().endswith(";")
                          and not re.match(r"^(namespace|struct|class|enum|using|template)\b", line))
                if starts:
                    j = i
                    while j < len(lines) and j - i < 6 and not lines[j].rstrip().endswith(("{", ";")):
                        j += 1
                    if j < len(lines) and lines[j].rstrip().endswith("{"):
                        k = j + 1
                        while k < len(lines) and not lines[k].startswith("}"):
                            k += 1
                        if k - i + 1 > limit:
                            long_functions.append((k - i + 1, relative, line.strip()[:80]))
                        i = k + 1
                        continue
                i += 1
print(f"functions over {limit} lines: {len(long_functions)}")
for entry in sorted(long_functions, reverse=True):
    print(f"  {entry[0]:5d}  {entry[1]}  {entry[2]}")
print(f"files over 900 lines: {len(long_files)}")
for entry in sorted(long_files, reverse=True):
    print(f"  {entry[0]:5d}  {entry[1]}")
