#!/usr/bin/env bash
# Do two twoball builds give the same results to the byte? Runs the scenes every speed-only
# change of the solver is checked on, with both binaries, and compares their history.csv and
# their results.json less the wall and CPU times (keys wall_time_s, cpu_time_s):
#   1. the default scene (the meridian section of two identical balls, subcycled, with its
#      default error estimate), and the same scene refined to `--tolerance 0.5%` (the banded,
#      mass-scaled section family);
#   2. ball 1 on a rigid wall (verification/wall.toml, on the section);
#   3. the default scene on the 3D quarter model (`reduction.symmetry = "auto-3d"`);
#   4. the default scene single-rate (no subcycling) on one thread, and on two threads with
#      the finer D/10 bulk mesh (7936 elements: models under 5000 elements run on one
#      thread whatever RAYON_NUM_THREADS says, so the default mesh would not test two), both
#      on the section and on the 3D quarter model;
#   5. a B-bar half model with tangential speed (ball-ball frictional contact).
# Usage: scripts/same_results.sh [--common] OLD_BINARY NEW_BINARY   (exit 0: all equal)
# With --common (builds far apart, whose outputs have gained columns or keys since), each
# scene compares only what OLD writes (scripts/common_outputs.py): OLD's history.csv columns
# and results.json values must stand in NEW unchanged; texts that differ are listed.
set -euo pipefail
common=0
if [ "${1:-}" = --common ]; then
  common=1
  shift
fi
if [ $# -ne 2 ]; then
  echo "usage: $0 [--common] OLD_BINARY NEW_BINARY" >&2
  exit 2
fi
old=$1
new=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
# results.json without the keys that measure time on the clock, keys sorted.
untimed() {
  jq -S 'walk(if type == "object" then del(.wall_time_s, .cpu_time_s) else . end)' "$1"
}
check() {
  local name=$1 threads=$2
  shift 2
  for side in old new; do
    local bin=$old
    [ "$side" = new ] && bin=$new
    if ! RAYON_NUM_THREADS=$threads "$bin" run "$@" --out "$work/$name-$side" \
      >/dev/null 2>"$work/$name-$side.err"; then
      echo "FAILED: $name ($side binary): $(tail -n 1 "$work/$name-$side.err")"
      status=1
      return
    fi
    untimed "$work/$name-$side/results.json" >"$work/$name-$side/results.untimed.json"
  done
  if [ $common = 1 ]; then
    if python3 "$here/common_outputs.py" "$work/$name-old" "$work/$name-new" >"$work/$name.common"; then
      echo "same numbers: $name"
    else
      echo "DIFFERENT: $name"
      status=1
    fi
    sed 's/^/  /' "$work/$name.common"
    return
  fi
  local differ=""
  for f in history.csv results.untimed.json; do
    cmp -s "$work/$name-old/$f" "$work/$name-new/$f" || differ="$differ $f"
  done
  if [ -z "$differ" ]; then
    echo "same: $name"
  else
    echo "DIFFERENT: $name ($differ )"
    status=1
  fi
}
d10=(--set 'ball1.mesh={size=0.002,pole_size=0.0001}' --set 'ball2.mesh={size=0.002,pole_size=0.0001}')
check default 1
check tolerance-0.5% 1 --tolerance 0.5%
check wall 1 "$here/../verification/wall.toml"
check default-3d 1 --set 'reduction.symmetry="auto-3d"'
check single-rate-1-thread 1 --set 'solver.subcycling="off"'
check single-rate-2-threads 2 --set 'solver.subcycling="off"' "${d10[@]}"
check 3d-d10-2-threads 2 --set 'reduction.symmetry="auto-3d"' "${d10[@]}"
check bbar-half-model 1 --set 'solver.element="b-bar"' \
  --set 'ball1.velocity=[1.0,0.5,0.0]' --set 'ball2.velocity=[-1.0,-0.5,0.0]'
exit $status
