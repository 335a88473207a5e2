#!/usr/bin/env bash
# Issue 16: `pip install .` with Debian's own Python tooling (python3-venv, pip, setuptools, wheel;
# numpy and pytest from Debian; nothing downloaded: --no-index), into a scratch virtual
# environment, then the Python tests run against the installed module from outside the source
# tree (no PYTHONPATH), so they import what pip installed.
# Usage: pip_install.sh SOURCE_DIR BUILD_DIR WORK_DIR   (BUILD_DIR: the CMake tree to build in)
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
py=$work/venv/bin/python
# pip builds in the source tree (setup.cfg puts setuptools' scratch in build/setuptools; the
# egg-info beside setup.py is ignored by git).
CTMAP_CMAKE_BUILD_DIR=$build PIP_NO_CACHE_DIR=1 "$py" -m pip install --no-build-isolation --no-index \
  --quiet "$src" > "$work/pip.log" 2>&1 || { cat "$work/pip.log"; exit 1; }
"$py" -m pip show ctmap | grep -E '^(Name|Version|Location):'
cd "$work"
unset PYTHONPATH
where=$("$py" -c 'import ctmap, os; print(os.path.realpath(ctmap.__file__))')
echo "import ctmap: $where"
case $where in
  "$(realpath "$work")"/venv/*) ;;
  *) echo "ctmap was not imported from the virtual environment"; exit 1 ;;
esac
PYTHONDONTWRITEBYTECODE=1 "$py" -m pytest -q -p no:cacheprovider "$src/python/tests"
