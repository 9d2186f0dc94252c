"""Checks durable publishing (issue 41) in an strace log.

Usage: durable_check.py TRACE CWD PUBLISHED...

TRACE is `strace -f -y -e trace=openat,fsync,fdatasync,rename,renameat,renameat2,mkdir,mkdirat`
output; CWD resolves the relative paths of `rename`. For every rename that succeeded:
  - a file renamed was flushed (fsync or fdatasync of a descriptor on that path, after the path
    was last opened for writing) before the rename;
  - a folder renamed (a staging folder published): every file in the folder as published
    (DIR, at the end of the run) was flushed under its staging name, or arrived there by a rename
    of a flushed file, and every folder of it was flushed after the last change of its entries,
    all before the rename;
  - the folder the rename wrote into was flushed after it.
Each PUBLISHED path (relative to CWD) must be covered: a rename's target, or inside a folder
renamed into place. Prints "ok: ..." and exits 0, or lists what is missing and exits 1.
"""
import os
import re
import sys

LINE = re.compile(r"^(\d+)\s+(.*)$")
CALL = re.compile(r"^(\w+)\((.*)$")
RESUMED = re.compile(r"^<\.\.\. (\w+) resumed>(.*)$")
RESULT = re.compile(r"\)\s+=\s+(-?\d+)(?:<(.*)>)?(?:\s.*)?$")
STRING = re.compile(r'"((?:[^"\\]|\\.)*)"')
DIRFD = re.compile(r"^\s*(?:AT_FDCWD|\d+)(?:<(.*?)>)?\s*,\s*")


def unescape(text):
    out = bytearray()
    k = 0
    while k < len(text):
        c = text[k]
        if c != "\\":
            out += c.encode()
            k += 1
            continue
        nxt = text[k + 1]
        if nxt == "x":
            out.append(int(text[k + 2 : k + 4], 16))
            k += 4
        elif nxt in "01234567":
            m = re.match(r"[0-7]{1,3}", text[k + 1 :])
            out.append(int(m.group(0), 8))
            k += 1 + len(m.group(0))
        else:
            out += {"n": b"\n", "t": b"\t", "r": b"\r", "v": b"\v", "f": b"\f"}.get(nxt, nxt.encode())
            k += 2
    return out.decode(errors="surrogateescape")


def events(trace_path):
    """(name, args, result, result_path, start, end) per completed system call, in the order
    strace saw them complete; start and end are line numbers of its entry and its result."""
    pending = {}
    calls = []
    with open(trace_path, encoding="utf-8", errors="surrogateescape") as f:
        for number, raw in enumerate(f):
            m = LINE.match(raw.rstrip("\n"))
            if not m:
                continue
            pid, rest = m.groups()
            resumed = RESUMED.match(rest)
            if resumed:
                name, tail = resumed.groups()
                if pid not in pending:
                    continue
                start, head = pending.pop(pid)
                text, start_line = head + tail, start
            else:
                call = CALL.match(rest)
                if not call:
                    continue
                if rest.endswith("<unfinished ...>"):
                    pending[pid] = (number, rest[: -len("<unfinished ...>")])
                    continue
                text, start_line = rest, number
                name = call.group(1)
            call = CALL.match(text)
            result = RESULT.search(text)
            if not call or not result:
                continue
            calls.append((call.group(1), call.group(2)[: result.start() - len(call.group(1)) - 1],
                          int(result.group(1)), result.group(2), start_line, number))
    return calls


def absolute(path, base):
    return os.path.normpath(path if path.startswith("/") else os.path.join(base, path))


def path_args(args, cwd, count):
    """The first `count` paths of a call: "path" or DIRFD, "path" pairs."""
    paths = []
    rest = args
    while len(paths) < count:
        base = cwd
        d = DIRFD.match(rest)
        if d and not rest.lstrip().startswith('"'):
            if d.group(1):
                base = d.group(1)
            rest = rest[d.end():]
        s = STRING.search(rest)
        if not s:
            break
        paths.append(absolute(unescape(s.group(1)), base))
        rest = rest[s.end():].lstrip(", ")
    return paths


def main():
    trace, cwd = sys.argv[1], os.path.realpath(sys.argv[2])
    published = [absolute(p, cwd) for p in sys.argv[3:]]
    syncs = {}         # path -> [(start, end)] of fsync / fdatasync
    write_opens = {}   # path -> [end] of openat for writing
    changes = {}       # folder -> [end] of changes of its entries (create, rename in or out, mkdir)
    renames = []       # (src, dst, start, end)
    for name, args, ret, ret_path, start, end in events(trace):
        if ret < 0:
            continue
        if name in ("fsync", "fdatasync"):
            m = re.match(r"\s*\d+<(.*)>", args)
            if m:
                syncs.setdefault(os.path.normpath(unescape(m.group(1))), []).append((start, end))
        elif name == "openat":
            if ret_path and re.search(r"O_WRONLY|O_RDWR|O_CREAT|O_TRUNC", args):
                p = os.path.normpath(unescape(ret_path))
                write_opens.setdefault(p, []).append(end)
                if "O_CREAT" in args:
                    changes.setdefault(os.path.dirname(p), []).append(end)
        elif name in ("mkdir", "mkdirat"):
            p = path_args(args, cwd, 1)
            if p:
                changes.setdefault(os.path.dirname(p[0]), []).append(end)
        elif name in ("rename", "renameat", "renameat2"):
            p = path_args(args, cwd, 2)
            if len(p) == 2:
                renames.append((p[0], p[1], start, end))
                changes.setdefault(os.path.dirname(p[0]), []).append(end)
                changes.setdefault(os.path.dirname(p[1]), []).append(end)

    def synced_between(path, after, before):
        return any(s_start > after and s_end < before for s_start, s_end in syncs.get(path, []))

    def file_durable(path, before, depth=0):
        """The file at `path` is on disk as of line `before`: flushed since last opened for
        writing, or renamed there from a file that was."""
        last_open = max([e for e in write_opens.get(path, []) if e < before], default=-1)
        if synced_between(path, last_open, before):
            return True
        arrivals = [r for r in renames if r[1] == path and r[3] < before]
        if arrivals and depth < 8:
            src, _, r_start, _ = max(arrivals, key=lambda r: r[3])
            return file_durable(src, r_start, depth + 1)
        return False

    def folder_durable(path, before):
        last_change = max([e for e in changes.get(path, []) if e < before], default=-1)
        return synced_between(path, last_change, before)

    problems = []
    covered = set()
    files_checked = folders_checked = 0
    for index, (src, dst, start, end) in enumerate(renames):
        later = [r for r in renames[index + 1:] if r[1] == dst]
        is_folder = src not in write_opens and os.path.isdir(dst) and not later
        if src not in write_opens and not is_folder and later:
            pass  # a folder replaced by a later rename: its content is checked at the last one
        elif is_folder:
            folders_checked += 1
            covered.add(dst)
            for root, dirs, files in os.walk(dst):
                rel = os.path.relpath(root, dst)
                staged_root = os.path.normpath(os.path.join(src, rel))
                covered.add(root)
                if not folder_durable(staged_root, start):
                    problems.append(f"folder {staged_root} (published as {root}) not flushed before its rename")
                for f in files:
                    covered.add(os.path.join(root, f))
                    if not file_durable(os.path.join(staged_root, f), start):
                        problems.append(f"file {os.path.join(staged_root, f)} (published as "
                                        f"{os.path.join(root, f)}) not flushed before the folder's rename")
        else:
            files_checked += 1
            covered.add(dst)
            if not file_durable(src, start):
                problems.append(f"file {src} not flushed before its rename to {dst}")
        parent = os.path.dirname(dst)
        if not any(s_start > end for s_start, _ in syncs.get(parent, [])):
            problems.append(f"folder {parent} not flushed after the rename of {src} to {dst}")

    for p in published:
        if p not in covered:
            problems.append(f"{p} was not published by a rename the trace shows")
    if problems:
        for p in problems[:40]:
            print("durable_check:", p)
        if len(problems) > 40:
            print(f"durable_check: ... and {len(problems) - 40} more")
        print(f"durable_check: {len(problems)} problems in {len(renames)} renames "
              f"({sum(len(v) for v in syncs.values())} syncs in the trace)")
        return 1
    print(f"ok: {len(renames)} renames, {files_checked} files and {folders_checked} folders published, "
          f"{sum(len(v) for v in syncs.values())} syncs; {len(published)} expected paths covered")
    return 0


if __name__ == "__main__":
    sys.exit(main())
