#!/usr/bin/env bash
# Issue 16, must-shows 2 and 3: installs the build into a scratch prefix, checks that the installed
# core library needs no OpenGL symbol (nm), then builds examples/find_package against the
# installed package alone (find_package(ctmap)) and maps the shipped example with it.
# Usage: install_consumer.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
core=$(find "$work/prefix" -name libctmap.a | head -1)
render=$(find "$work/prefix" -name libctmap_render.a | head -1)
[ -n "$core" ] && [ -n "$render" ] || { echo "libctmap.a or libctmap_render.a was not installed"; exit 1; }
gl() { nm --undefined-only "$1" | grep -cE ' (gl[A-Z]|egl[A-Z])' || true; }
echo "OpenGL/EGL symbols needed: core library $(gl "$core"), render library $(gl "$render")"
[ "$(gl "$core")" = 0 ] || { echo "the core library needs OpenGL symbols"; exit 1; }
[ "$(gl "$render")" -gt 0 ] || { echo "control failed: the render library needs no OpenGL symbol"; exit 1; }
cmake -S "$src/examples/find_package" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/example" -j2 > "$work/build.log"
# The shipped example, found as the library finds it (data_path.cpp's order).
for d in "${CTMAP_DATA:-}" "$src/data" "$src/../shared/data" "$src/.cache/data"; do
  [ -n "$d" ] && [ -f "$d/meshes/nefertiti.off" ] && { data=$d; break; }
done
[ -n "${data:-}" ] || { echo "no example data (scripts/fetch_data.sh)"; exit 1; }
"$work/example/map_example" "$data/meshes/nefertiti.off" "$data/features/nefertiti_astronaut.json"
