#!/usr/bin/env bash
# Configures and builds ctmap. Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
# CTMAP_BUILD_TARGETS="ctmap ...": build only those targets (default: everything the tree has).
# Two parallel jobs: the machines have 2 cores and CGAL's translation units are heavy. The sources
# are compiled in batches (cmake/ctmap_unity.cmake); ccache and mold are used when installed.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build}
shift || true
# three.js for the page of `ctmap serve` (web/), exactly as web/package-lock.json pins it.
if command -v npm >/dev/null && [ ! -f web/node_modules/three/build/three.module.js ]; then
  (cd web && npm ci --no-audit --no-fund >/dev/null)
fi
# (before configuring: the install rules copy it when it is there)
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S . -B "$dir" "${gen[@]}" "$@" >/dev/null
else
  cmake -S . -B "$dir" "$@" >/dev/null
fi
targets=()
for t in ${CTMAP_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$dir" -j2 ${targets[@]+"${targets[@]}"}
