#!/usr/bin/env bash
# Do two twoball builds give the same results to the byte? Runs the scenes every speed-only
# change of the solver is checked on, with both binaries, and compares their history.csv:
#   1. the default scene (quarter model, subcycled, one thread),
#   2. the default scene single-rate (no subcycling) on one thread, and on two threads with
#      the finer D/10 bulk mesh (7936 elements: models under 5000 elements run on one
#      thread whatever RAYON_NUM_THREADS says, so the default mesh would not test two),
#   3. a B-bar half model with tangential speed (ball-ball frictional contact).
# Usage: scripts/same_results.sh OLD_BINARY NEW_BINARY   (exit 0: all equal)
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY" >&2
  exit 2
fi
old=$1
new=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
check() {
  local name=$1 threads=$2
  shift 2
  for side in old new; do
    local bin=$old
    [ "$side" = new ] && bin=$new
    RAYON_NUM_THREADS=$threads "$bin" run "$@" --out "$work/$name-$side" >/dev/null
  done
  if cmp -s "$work/$name-old/history.csv" "$work/$name-new/history.csv"; then
    echo "same: $name"
  else
    echo "DIFFERENT: $name"
    status=1
  fi
}
check default 1
check single-rate-1-thread 1 --set 'solver.subcycling="off"'
check single-rate-2-threads 2 --set 'solver.subcycling="off"' \
  --set 'ball1.mesh={size=0.002,pole_size=0.0001}' --set 'ball2.mesh={size=0.002,pole_size=0.0001}'
check bbar-half-model 1 --set 'solver.element="b-bar"' \
  --set 'ball1.velocity=[1.0,0.5,0.0]' --set 'ball2.velocity=[-1.0,-0.5,0.0]'
exit $status
