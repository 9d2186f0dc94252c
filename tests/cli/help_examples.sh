#!/bin/sh
# help_examples.sh WANGSCAPE SOURCE SCRATCH: every subcommand's --help (the program's too) ends
# with "Writes: ..." and "Examples (from the repository root):" followed by two or three command
# lines, and every one of those lines works. They run in order of a depth-first walk, each
# distinct line once (a later help's `wangscape build ... --out small` reuses the first), in
# SCRATCH, which links the checkout's data/ and templates/ as the repository root has them, with
# this wangscape first on PATH; each must exit 0.
# Not run (they take half a minute or more, 80 s of the test's budget of 60): `wangscape demo
# --out` (the default scene rendered by POV-Ray), `wangscape batch run` (four stills of it) and
# `wangscape batch status` of that run's folder; HELP_EXAMPLES_ALL=1 runs them too.
bin=$(realpath "$1")
src=$(realpath "$2")
scratch=$3
rm -rf "$scratch"
mkdir -p "$scratch"
ln -s "$src/data" "$scratch/data"
ln -s "$src/templates" "$scratch/templates"
PATH="$(dirname "$bin"):$PATH"
export PATH
status=0
fail() { echo "help_examples: $*" >&2; status=1; }
: > "$scratch/.ran"
walk() {
  # $@: the subcommand path ("" for the program itself)
  help=$("$bin" "$@" --help 2>&1) || { fail "'wangscape $*' --help failed"; return; }
  printf '%s\n' "$help" | grep -q '^Writes: ' || fail "'wangscape $* --help' does not say what it writes"
  examples=$(printf '%s\n' "$help" | sed -n '/^Examples (from the repository root):$/,/^$/p' | sed -n 's/^  \(wangscape .*\)$/\1/p')
  count=$(printf '%s\n' "$examples" | grep -c '^wangscape ')
  if [ "$count" -lt 2 ] || [ "$count" -gt 3 ]; then
    fail "'wangscape $* --help' ends with $count examples, expected 2 or 3"
  fi
  printf '%s\n' "$examples" | while IFS= read -r line; do
    [ -n "$line" ] || continue
    grep -qxF -- "$line" "$scratch/.ran" && continue
    printf '%s\n' "$line" >> "$scratch/.ran"
    case "$line" in
    "wangscape demo --out"* | "wangscape batch run"* | "wangscape batch status"*)
      if [ "${HELP_EXAMPLES_ALL:-0}" != 1 ]; then
        echo "skipped: $line"
        continue
      fi
      ;;
    esac
    start=$(date +%s.%N)
    if (cd "$scratch" && sh -c "$line" > "$scratch/.out" 2>&1); then
      echo "ok ($(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s): $line"
    else
      echo "help_examples: 'wangscape $* --help': example failed: $line" >&2
      sed 's/^/    /' "$scratch/.out" >&2
      echo fail >> "$scratch/.failed"
    fi
  done
  for sub in $(printf '%s\n' "$help" | sed -n '/^Subcommands:/,/^$/p' | sed -n 's/^  \([a-z][a-z-]*\) .*/\1/p'); do
    walk "$@" "$sub"
  done
}
walk
[ -e "$scratch/.failed" ] && status=1
exit $status
