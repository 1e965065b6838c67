#!/usr/bin/env bash
# The Python front's pytest suite N times in a row (default 20) while another twoball release
# run keeps the machine busy beside it: the check that its tests depend on no timing luck.
# Needs the package built by `cargo test --test suite python_front:: -- --ignored` (it makes the
# virtual environment under target/python-front) and a release build (`cargo build --release`).
# Usage: bash scripts/pytest_loop.sh [N]. Prints one line a pass and exits non-zero on the first failure.
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-20}"
python="target/python-front/venv/bin/python"
bin="target/release/twoball"
[ -x "$python" ] || { echo "pytest_loop.sh: $python missing: first run cargo test --test suite python_front:: -- --ignored" >&2; exit 1; }
[ -x "$bin" ] || { echo "pytest_loop.sh: $bin missing: run cargo build --release first" >&2; exit 1; }
load="$(mktemp -d)"
# The load: the default scene on the 3D quarter model (a single-threaded run of seconds), over and over.
( while true; do "$bin" run --no-error-estimate --set 'reduction.symmetry="auto-3d"' --out "$load/run" >/dev/null 2>&1 || true; done ) &
loader=$!
trap 'kill "$loader" 2>/dev/null || true; wait "$loader" 2>/dev/null || true; rm -rf "$load"' EXIT
for i in $(seq 1 "$n"); do
  start=$(date +%s)
  if ! (cd python && TWOBALL_BIN="../$bin" PATH="$PWD/../target/python-front/venv/bin:$PATH" \
      "../$python" -m pytest -q -p no:cacheprovider tests >"$load/pytest.log" 2>&1); then
    cat "$load/pytest.log" >&2
    echo "pytest_loop.sh: pass $i of $n FAILED" >&2
    exit 1
  fi
  echo "pass $i of $n: $(tail -n 1 "$load/pytest.log") ($(( $(date +%s) - start )) s, load running)"
done
echo "pytest_loop.sh: $n passes in a row"
