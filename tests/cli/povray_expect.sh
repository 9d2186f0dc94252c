#!/bin/sh
# povray_expect.sh CODE PATTERN COMMAND...: runs COMMAND, passes when it exits with CODE and its
# output (stdout + stderr) matches the grep -E PATTERN (empty pattern: any output).
code=$1
pattern=$2
shift 2
out=$("$@" 2>&1)
got=$?
printf '%s\n' "$out"
if [ "$got" -ne "$code" ]; then
  echo "povray_expect: exit code $got, expected $code" >&2
  exit 1
fi
if [ -n "$pattern" ] && ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  echo "povray_expect: output does not match: $pattern" >&2
  exit 1
fi
exit 0
