#!/usr/bin/env bash
# Makes the example meshes and images available. They are looked for in $CTMAP_DATA, then
# ../shared/data beside the project; when neither has them, they are taken from Debian's own
# packages (libcgal-demo for CGAL's meshes, python3-skimage for scikit-image's photographs) into
# .cache/data, without installing those packages.
set -euo pipefail
cd "$(dirname "$0")/.."
# The closed, multi-border and higher-genus meshes of the charts (issue 13) come from libcgal-demo
# (scripts/install_deps.sh installs it): taken from its data archive into .cache/data/meshes.
extra_meshes=(bull homer man bunny00 elk elephant head holes)
fetch_extra_meshes() {
  local missing=() m d found
  for m in "${extra_meshes[@]}"; do
    found=""
    for d in "${CTMAP_DATA:-}" ../shared/data .cache/data; do
      if [ -n "$d" ] && [ -f "$d/meshes/$m.off" ]; then found=1; break; fi
    done
    [ -n "$found" ] || missing+=("$m")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local archive=/usr/share/doc/libcgal-dev/data.tar.gz
  if [ ! -f "$archive" ]; then
    echo "data: $archive missing (package libcgal-demo): the charts tests on ${missing[*]} will fail" >&2
    return 0
  fi
  mkdir -p .cache/data/meshes
  local paths=()
  for m in "${missing[@]}"; do paths+=("data/meshes/$m.off"); done
  tar xzf "$archive" -C .cache/data/meshes --strip-components=2 "${paths[@]}"
  echo "data: ${missing[*]} from $archive into .cache/data/meshes"
}
fetch_extra_meshes
have() { [ -f "$1/meshes/nefertiti.off" ] && [ -f "$1/images/astronaut.png" ]; }
for d in "${CTMAP_DATA:-}" ../shared/data .cache/data; do
  if [ -n "$d" ] && have "$d"; then echo "data: using $d"; exit 0; fi
done
echo "data: fetching CGAL's meshes and scikit-image's images from Debian packages into .cache/data"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download libcgal-demo python3-skimage >/dev/null 2>&1) || {
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  (cd "$work" && apt-get download libcgal-demo python3-skimage)
}
for deb in "$work"/*.deb; do dpkg -x "$deb" "$work/x"; done
mkdir -p "$work/cgal" .cache/data/meshes .cache/data/images
tar xzf "$work/x/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work/cgal"
for m in nefertiti mannequin-devil lion-head mushroom three_peaks cow; do
  cp "$work/cgal/data/meshes/$m.off" .cache/data/meshes/
done
for i in astronaut chelsea coffee; do
  cp "$work/x/usr/lib/python3/dist-packages/skimage/data/$i.png" .cache/data/images/
done
echo "data: $(ls .cache/data/meshes | wc -l) meshes, $(ls .cache/data/images | wc -l) images in .cache/data"
