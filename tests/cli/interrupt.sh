#!/bin/sh
# interrupt.sh SIGNAL CODE DIR PATTERN COMMAND...: runs COMMAND in the background, waits until
# a file or folder matching PATTERN (a shell glob, e.g. '.*tmp-*') appears in DIR (the run has
# started writing), sends SIGNAL, and passes when the run exits with CODE and leaves nothing
# matching '.tmp-*', '.*.tmp-*' or '.*.partial-*' in DIR. Before the run it plants a temporary of a dead
# process (must be removed) and one of this live shell (must stay).
signal=$1
code=$2
dir=$3
pattern=$4
shift 4
fail() {
  echo "interrupt: $*" >&2
  exit 1
}
mkdir -p "$dir" || fail "cannot create $dir"
rm -rf "$dir"/.tmp-* "$dir"/.*.tmp-* "$dir"/.*.partial-*
# A pid no process has: the highest below pid_max that kill -0 reports gone.
dead=$(($(cat /proc/sys/kernel/pid_max) - 1))
while kill -0 "$dead" 2>/dev/null; do dead=$((dead - 1)); done
: >"$dir/.tmp-$dead-stale.csv"
mkdir "$dir/.stale.partial-$dead"
live_file="$dir/.tmp-$$-live.csv"
: >"$live_file"

# A shell starts background jobs with SIGINT ignored, which wangscape (rightly) keeps: undo that.
env --default-signal=INT "$@" >/dev/null 2>"$dir/interrupt.err" &
pid=$!
. "$(dirname "$0")/wait_for_start.sh"
wait_for_start "$pid" "$dir" "$pattern" 40 || {
  kill -KILL "$pid" 2>/dev/null
  fail "the run never started writing ($pattern in $dir); stderr: $(cat "$dir/interrupt.err")"
}
sleep 0.2
kill "-$signal" "$pid"
wait "$pid"
got=$?
cat "$dir/interrupt.err"
[ "$got" -eq "$code" ] || fail "exit code $got after SIG$signal, expected $code"
left=$(find "$dir" -maxdepth 2 \( -name '.tmp-*' -o -name '.*.tmp-*' -o -name '.*.partial-*' \) ! -path "$live_file")
[ -z "$left" ] || fail "left behind: $left"
[ -e "$live_file" ] || fail "removed $live_file of a live process"
rm -f "$live_file"
echo "interrupt: SIG$signal -> exit $got, nothing left in $dir"
exit 0
