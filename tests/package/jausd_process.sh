# Sourced by the package tests (install_and_build_component.sh, check_deb.sh):
# a temporary folder, a jausd they start in the background and always stop,
# waiting for a condition, and jausd's orderly stop on SIGTERM.
# The sourcing script sets `work` (its temporary folder) first, and puts the
# started jausd's pid in `jausd_pid`, its log in "$work/jausd.log".
jausd_pid=""
cleanup() {
  if [ -n "$jausd_pid" ]; then kill -KILL "$jausd_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }

# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local seconds=$1; shift
  local deadline=$((SECONDS + seconds))
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || return 1
    sleep 0.2
  done
}

# SIGTERM to jausd, which must exit 0 (an orderly stop); a stop that hangs is
# killed after 30 s and fails with 137.
stop_jausd() {
  kill -TERM "$jausd_pid"
  (sleep 30 && kill -KILL "$jausd_pid") > /dev/null 2>&1 &
  local watchdog=$! status=0
  wait "$jausd_pid" || status=$?
  kill "$watchdog" 2> /dev/null || true
  jausd_pid=""
  [ "$status" -eq 0 ] || { cat "$work/jausd.log"; fail "jausd exited $status after SIGTERM"; }
}
