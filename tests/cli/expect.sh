#!/bin/sh
# expect.sh CODE PATTERN COMMAND...: runs COMMAND, passes when it exits with CODE and its
# output (stdout + stderr) matches the grep -E PATTERN (empty pattern: any output). CTest
# ignores exit codes once PASS_REGULAR_EXPRESSION is set, so CLI tests check both here.
code=$1
pattern=$2
shift 2
out=$("$@" 2>&1)
got=$?
printf '%s\n' "$out"
if [ "$got" -ne "$code" ]; then
  echo "expect: exit code $got, expected $code" >&2
  exit 1
fi
if [ -n "$pattern" ] && ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  echo "expect: output does not match: $pattern" >&2
  exit 1
fi
exit 0
