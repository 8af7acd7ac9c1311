#!/usr/bin/env bash
# Install everything tribofx needs on a Debian 12 machine with Python 3.12 (on PATH,
# under pyenv, or PYTHON=...): the X/GL runtime
# libraries of the gmsh wheel (apt), a Python 3.12 virtual environment with the
# DOLFINx 0.11 wheel (dolfinx-solver-real: PETSc, SLEPc, petsc4py, MPICH), the
# Python tools, and the package with its C++ extension (scikit-build-core).
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}

apt_pkgs="libglu1-mesa libgl1 libxrender1 libxcursor1 libxfixes3 libxext6 libxft2 \
libfontconfig1 libxinerama1 libx11-6 libgomp1 make g++"
missing=""
for p in $apt_pkgs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "setup: installing Debian packages:$missing"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install:$missing" >&2; exit 1; }
    SUDO="sudo"
  fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi

find_python() {
  for c in "${PYTHON:-}" python3.12 "$HOME"/.pyenv/versions/3.12*/bin/python3.12 \
           /usr/local/bin/python3.12 /usr/bin/python3.12; do
    [ -n "$c" ] || continue
    if "$c" -c 'import sys; assert sys.version_info[:2] == (3, 12)' >/dev/null 2>&1; then
      echo "$c"; return 0
    fi
  done
  return 1
}

if [ ! -x "$VENV/bin/python" ]; then
  PY=$(find_python) || { echo "setup: Python 3.12 not found: install it (Debian 12 ships 3.11: 'pyenv install 3.12' or deadsnakes), or set PYTHON=/path/to/python3.12" >&2; exit 1; }
  echo "setup: creating $VENV with $PY"
  "$PY" -m venv "$VENV"
fi
# the exact versions of constraints.txt (UNLOCKED=1: the newest, for `make lock`)
LOCK=(-c constraints.txt)
[ "${UNLOCKED:-0}" = 1 ] && LOCK=()
"$VENV/bin/python" -m pip install -q "${LOCK[@]}" --upgrade pip
"$VENV/bin/python" -m pip install -q "${LOCK[@]}" "dolfinx-solver-real==0.11.0.post0" gmsh meshio \
  matplotlib tqdm pytest pytest-xdist ruff mypy nanobind scikit-build-core numpy cmake ninja
"$VENV/bin/python" -m pip install -q "${LOCK[@]}" --no-build-isolation -e .
UCX_TLS=self,sm,tcp "$VENV/bin/python" -c "import dolfinx_solver, dolfinx, gmsh, tribofx._cpp; print('setup: dolfinx', dolfinx.__version__, 'gmsh', gmsh.__version__, 'tribofx ok')"
