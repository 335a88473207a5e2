#!/usr/bin/env bash
# Configures and builds ctmap. Usage: scripts/build.sh [BUILD_DIR] [extra cmake args...]
# Two parallel jobs: the machines have 2 cores and CGAL's translation units are heavy.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build}
shift || true
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S . -B "$dir" "${gen[@]}" "$@" >/dev/null
else
  cmake -S . -B "$dir" "$@" >/dev/null
fi
cmake --build "$dir" -j2
