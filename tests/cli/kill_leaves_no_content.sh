#!/bin/sh
# kill_leaves_no_content.sh DIR PATTERN SUFFIX COMMAND...: runs COMMAND in a session of its own,
# waits until a temporary matching the shell glob DIR/PATTERN names the run (it has started
# writing), kills the whole session with SIGKILL (no cleanup can run), and passes when nothing
# in DIR ends in SUFFIX: what a killed run leaves is a temporary no reader of the folder takes
# for content (a listing of *.png finds no half-written image).
dir=$1
pattern=$2
suffix=$3
shift 3
fail() {
  echo "kill_leaves_no_content: $*" >&2
  exit 1
}
[ -d "$dir" ] || fail "no folder $dir"
find "$dir" -name "*$suffix" -delete
# setsid: the run leads its own process group, so the kill reaches its children (POV-Ray) too.
setsid "$@" >/dev/null 2>"$dir/kill.err" &
pid=$!
. "$(dirname "$0")/wait_for_start.sh"
wait_for_start "$pid" "$dir" "$pattern" 60 || {
  kill -KILL "-$pid" 2>/dev/null
  fail "the run never started writing ($pattern in $dir); stderr: $(cat "$dir/kill.err")"
}
sleep 0.5
kill -KILL "-$pid"
wait "$pid"
left=$(find "$dir" -name "*$suffix")
[ -z "$left" ] || fail "a killed run left a file a reader takes for content: $left"
temps=$(find "$dir" -name ".*.tmp-$pid")
[ -n "$temps" ] || fail "expected the killed run's temporaries (.*.tmp-$pid) in $dir, found none"
echo "kill_leaves_no_content: SIGKILL left only $(echo "$temps" | wc -l) hidden temporaries, no *$suffix"
