# Sourced by scripts/test.sh and scripts/sanitize.sh: `phase NAME COMMAND...` runs the
# command and prints its wall time as "time: NAME N s" (CI's log shows where the time
# goes); a failing command stops the script as it would have without it.
phase() {
  local name="$1" start=$SECONDS
  shift
  "$@"
  echo "time: $name $((SECONDS - start)) s"
}
