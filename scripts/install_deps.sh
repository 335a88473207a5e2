#!/usr/bin/env bash
# Installs ctmap's build and test dependencies from Debian's packages (DESIGN §5).
# Does nothing when they are all present, so the test command can call it cheaply.
# Usage: install_deps.sh [PACKAGE...]
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  ccache mold  # faster rebuilds and links (scripts/build.sh uses them when present; never required)
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libcgal-demo  # CGAL's meshes: the closed and higher-genus ones of the charts tests (scripts/fetch_data.sh)
  # libopenblas0-pthread: an optimised BLAS for CHOLMOD's supernodal factorisation (refine/isometric)
  libeigen3-dev libtbb-dev nlohmann-json3-dev libcli11-dev libstb-dev libjpeg62-turbo-dev libtinygltf-dev libexif-dev libcpp-httplib-dev libsuitesparse-dev libopenblas0-pthread
  libgtest-dev libbenchmark-dev gnuplot-nox
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  clang-14 libclang-rt-14-dev llvm-14  # scripts/fuzz.sh: clang, libFuzzer's runtime, llvm-symbolizer
  nodejs chromium
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python bindings (python/) and their tests
  python3-venv python3-pip python3-setuptools python3-wheel  # `pip install .` (pyproject.toml, setup.py)
)
# npm ships inside NodeSource's nodejs; only a Debian nodejs needs Debian's npm beside it.
command -v npm >/dev/null || packages+=(npm)
# `install_deps.sh PACKAGE...`: those packages instead (the test command's own, e.g. blender for the
# add-on's test, which the set-up does not install).
[ $# -eq 0 ] || packages=("$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "dependencies: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "dependencies: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
