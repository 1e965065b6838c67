#!/usr/bin/env bash
# Installs what twoball's tests and studies drive besides Rust: gmsh (mesh pipeline) and
# meshio (independent check that .vtu files are readable). Safe to run repeatedly.
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null 2>&1; then SUDO=sudo; fi
if ! command -v gmsh >/dev/null 2>&1; then
  if command -v apt-get >/dev/null 2>&1; then
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends gmsh >/dev/null
  else
    python3 -m pip install --quiet gmsh
  fi
fi
if ! python3 -c "import meshio" >/dev/null 2>&1; then
  # Debian marks its Python as externally managed (PEP 668): prefer its own package.
  if command -v apt-get >/dev/null 2>&1; then
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
      python3-meshio >/dev/null 2>&1 || true
  fi
  # The apt package serves only the system interpreter; another python3 on PATH needs pip.
  if ! python3 -c "import meshio" >/dev/null 2>&1; then
    python3 -m pip install --quiet meshio || python3 -m pip install --quiet --break-system-packages meshio
  fi
fi
if ! command -v ccx >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends calculix-ccx >/dev/null; fi  # CalculiX peer (scripts/ccx_peer.py)
