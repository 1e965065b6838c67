#!/usr/bin/env bash
# Installs what twoball's tests and studies drive besides Rust: gmsh (mesh pipeline), meshio
# (independent check that .vtu files are readable), CalculiX ccx (the peer code) and the DEM
# codes the contact-law exports are run in (LIGGGHTS `liggghts`, LAMMPS `lmp`, Yade `yade`).
# Safe to run repeatedly. Exits non-zero, naming the program, when one cannot be installed.
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null 2>&1; then SUDO=sudo; fi
APT_UPDATED=""
apt_install() { # apt_install PACKAGE: install one Debian package (one apt-get update per run)
  if [ -z "$APT_UPDATED" ]; then $SUDO apt-get update -qq; APT_UPDATED=1; fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "$1" >/dev/null
}
if ! command -v gmsh >/dev/null 2>&1; then
  if command -v apt-get >/dev/null 2>&1; then apt_install gmsh; else python3 -m pip install --quiet gmsh; fi
fi
if ! python3 -c "import meshio" >/dev/null 2>&1; then
  # Debian marks its Python as externally managed (PEP 668): prefer its own package. The apt
  # package serves only the system interpreter; another python3 on PATH needs pip.
  if command -v apt-get >/dev/null 2>&1 && ! apt_install python3-meshio; then
    echo "setup.sh: apt-get install python3-meshio failed; trying pip" >&2
  fi
  if ! python3 -c "import meshio" >/dev/null 2>&1; then
    python3 -m pip install --quiet meshio || python3 -m pip install --quiet --break-system-packages meshio
  fi
fi
if ! command -v ccx >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then apt_install calculix-ccx; fi  # CalculiX peer (scripts/ccx_peer.py)
# The DEM codes of tests/suite/dem_exports.rs, from Debian's packages.
if command -v apt-get >/dev/null 2>&1; then
  command -v liggghts >/dev/null 2>&1 || apt_install liggghts
  command -v lmp >/dev/null 2>&1 || apt_install lammps
  command -v yade >/dev/null 2>&1 || apt_install yade
fi
# The Python front's test (tests/suite/python_front.rs) makes a virtual environment.
if ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then apt_install python3-venv; fi
# Check: every program the tests need is there (CI=true makes a missing one a test failure).
missing=""
command -v gmsh >/dev/null 2>&1 || missing="$missing gmsh"
python3 -c "import meshio, numpy" >/dev/null 2>&1 || missing="$missing meshio/numpy(python3)"
command -v ccx >/dev/null 2>&1 || missing="$missing ccx(calculix-ccx)"
python3 -c 'import venv, ensurepip' >/dev/null 2>&1 || missing="$missing venv(python3)"
command -v liggghts >/dev/null 2>&1 || missing="$missing liggghts"
command -v lmp >/dev/null 2>&1 || missing="$missing lmp(lammps)"
command -v yade >/dev/null 2>&1 || missing="$missing yade"
if [ -n "$missing" ]; then
  echo "setup.sh: not installed:$missing" >&2
  exit 1
fi
