#!/bin/sh
# refuse.sh CODE PATTERN COMMAND...: like expect.sh (exit CODE, output matching the grep -E
# PATTERN), and the output holds no raw library text (issue 25); COMMAND gets 30 s, not forever.
code=$1
pattern=$2
shift 2
out=$(timeout 30 "$@" 2>&1)
got=$?
printf '%s\n' "$out"
[ "$got" -eq "$code" ] || { echo "refuse: exit code $got, expected $code" >&2; exit 1; }
printf '%s\n' "$out" | grep -Eq -- "$pattern" || { echo "refuse: output does not match: $pattern" >&2; exit 1; }
if printf '%s\n' "$out" | grep -Eq 'json\.exception|filesystem error|basic_filebuf|std::|terminate called|libpng|OpenImageIO'; then
  echo "refuse: raw library text" >&2
  exit 1
fi
exit 0
