# wait_for_start PID DIR PATTERN [SECONDS]: sourced by the interrupt tests. Returns 0 once a path
# matching the shell glob DIR/PATTERN names the run PID (its temporaries carry "-PID-" or end in
# "-PID": the run has started writing), 1 when the run ended first or SECONDS (default 40) passed.
wait_for_start() {
  _pid=$1
  _dir=$2
  _pattern=$3
  _tries=$((${4:-40} * 10))
  while [ "$_tries" -gt 0 ]; do
    for _f in "$_dir"/$_pattern; do
      case "$_f" in *"-$_pid-"* | *"-$_pid") return 0 ;; esac
    done
    kill -0 "$_pid" 2>/dev/null || return 1
    sleep 0.1
    _tries=$((_tries - 1))
  done
  return 1
}
