#!/usr/bin/env bash
# The particle damper's sensitivity table (verification/damper/REPORT.md): the seven cases of
# Table 2 under each variation of the contact law, the friction coefficients, the box and the
# mass reading; one `twoball damper` command per row, printed in the table.
#
#   scripts/damper_sensitivity.sh [OUT_DIR] [ROW...]     (default OUT_DIR damper-sensitivity)
#
# TWOBALL names the binary (default target/release/twoball). Each row writes OUT_DIR/ROW/
# (summary.csv and the per-case histories); the table (damping ratio of every case in %, and
# the largest energy residual of the row) goes to stdout and OUT_DIR/table.md.
set -euo pipefail

cd "$(dirname "$0")/.."
BIN=${TWOBALL:-target/release/twoball}
OUT=${1:-damper-sensitivity}
shift || true
SCENE=verification/damper/table2.toml

# name|flags
ROWS=(
  "baseline|"
  "hertz-damped-e0.33|--law hertz-damped --param e=0.3292"
  "thornton|--law thornton"
  "frictionless|--mu-ball 0 --mu-wall 0"
  "mu-0.3|--mu-ball 0.3 --mu-wall 0.3"
  "box-101.1mm|--box 0.1011,0.039,0.035"
  "box-105mm|--box 0.105,0.039,0.035"
  "mass-2.68kg|--frame-mass 2.68"
  "glass-16mm|--diameter glass=0.016"
)

wanted() {
  [ $# -eq 0 ] && return 0
  local r
  for r in "${@:2}"; do [ "$r" = "$1" ] && return 0; done
  return 1
}

mkdir -p "$OUT"
for row in "${ROWS[@]}"; do
  name=${row%%|*}
  flags=${row#*|}
  if [ $# -gt 0 ] && ! wanted "$name" "$@"; then continue; fi
  # shellcheck disable=SC2086
  "$BIN" damper "$SCENE" --out "$OUT/$name" $flags > "$OUT/$name.log"
done

{
  printf '| row | command | 1 | 2 | 3 | 4 | 5 | 6 | 7 | energy residual |\n'
  printf '|---|---|---|---|---|---|---|---|---|---|\n'
  for row in "${ROWS[@]}"; do
    name=${row%%|*}
    flags=${row#*|}
    s="$OUT/$name/summary.csv"
    [ -f "$s" ] || continue
    cells=$(awk -F, 'NR > 1 { printf "| %.3f ", 100 * $6; if ($12 > w) w = $12; if (-$12 > w) w = -$12 }
                     END { printf "| %.1e |", w }' "$s")
    printf '| %s | `twoball damper %s --out DIR%s` %s\n' "$name" "$SCENE" "${flags:+ $flags}" "$cells"
  done
} | tee "$OUT/table.md"
