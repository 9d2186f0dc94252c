#!/bin/sh
# help_words.sh WANGSCAPE: prints the --help of every subcommand, depth first, and fails when one
# names a paper by its old working name ("seed 003") instead of saying what a thing does, or shows
# an option's type as CLI11's "TEXT x 2" instead of the words a user types.
bin=$1
status=0
walk() {
  # $@: the subcommand path ("" for the program itself)
  help=$("$bin" "$@" --help 2>&1) || { echo "help_words: '$*' --help failed" >&2; status=1; return; }
  printf '== wangscape %s\n%s\n' "$*" "$help"
  if printf '%s\n' "$help" | grep -Eiq 'seeds? 0[0-9][0-9]'; then
    echo "help_words: 'wangscape $* --help' names a paper by its seed number" >&2
    status=1
  fi
  # an option's left column (up to two spaces) must not end in " x N"
  if printf '%s\n' "$help" | sed -n 's/^  \(-[^ ].*\)$/\1/p' | sed 's/  .*//' | grep -Eq ' x [0-9]+$'; then
    echo "help_words: 'wangscape $* --help' shows a type as 'TYPE x N'" >&2
    status=1
  fi
  for sub in $(printf '%s\n' "$help" | sed -n '/^Subcommands:/,/^$/p' | sed -n 's/^  \([a-z][a-z-]*\) .*/\1/p'); do
    walk "$@" "$sub"
  done
}
walk
exit $status
