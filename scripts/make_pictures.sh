#!/usr/bin/env bash
# Redraws the README's pictures (docs/<case>_<mode>.png): each example mapped by `ctmap map`, then
# drawn in the five modes by `ctmap render` (issue 5). Usage: scripts/make_pictures.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
ctmap="${1:-build}/ctmap"
[ -x "$ctmap" ] || { echo "no $ctmap: build first (scripts/build.sh)" >&2; exit 2; }

# The data folders ctmap itself searches (src/ctmap/io/data_path.h), in the same order.
data() {
  for d in "${CTMAP_DATA:-}" data ../shared/data .cache/data; do
    [ -n "$d" ] && [ -f "$d/$1" ] && { echo "$d/$1"; return; }
  done
  echo "missing data file $1" >&2; exit 2
}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs
# case  mesh  features  image
while read -r name mesh features image; do
  "$ctmap" map "$(data "meshes/$mesh")" "$(data "features/$features")" --image "$(data "images/$image")" \
    -o "$work/$name.obj" --quiet
  "$ctmap" check "$work/$name.obj" --features "$(data "features/$features")" --image "$(data "images/$image")"
  for mode in textured checker paths; do
    "$ctmap" render "$work/$name.obj" -o "docs/${name}_$mode.png" --mode "$mode" \
      --features "$(data "features/$features")" --size 640
  done
  for mode in uv triangulation; do  # the image plane: the picture takes the region's aspect
    "$ctmap" render "$work/$name.obj" -o "docs/${name}_$mode.png" --mode "$mode" \
      --features "$(data "features/$features")" --size 512
  done
done <<'CASES'
nefertiti nefertiti.off nefertiti_astronaut.json astronaut.png
lion-head lion-head.off lion-head_chelsea.json chelsea.png
nefertiti-landmarks nefertiti.off nefertiti_landmarks.json astronaut.png
lion-head-landmarks lion-head.off lion-head_landmarks.json chelsea.png
CASES

# Morph strips (issue 14, paper Figs. 8-9): the shipped head pairs, five frames from source to target.
for pair in nefertiti:lion-head mannequin-devil:lion-head; do
  src=${pair%%:*}; dst=${pair##*:}
  "$ctmap" morph "$(data "meshes/$src.off")" "$(data "meshes/$dst.off")" "data/pairs/${src}_${dst}.json" \
    -o "$work/${src}_${dst}.glb" --strip "docs/morph_${src}_${dst}.png" --view three-quarter --frames 5
done

# Charts (issue 13, paper §3 Figs. 5-6): closed meshes with two charts, a photo and its mirror
# image (starter-features --charts 2), drawn from both sides of the seam; a closed head and a
# mesh with handles with one chart and the rest mapped automatically.
while read -r mesh image side1 side2; do
  "$ctmap" starter-features "$(data "meshes/$mesh.off")" --image "$(data "images/$image")" --charts 2 \
    -o "$work/${mesh}_charts.json"
  "$ctmap" map "$(data "meshes/$mesh.off")" "$work/${mesh}_charts.json" -o "$work/${mesh}_charts.obj" --quiet
  "$ctmap" check "$work/${mesh}_charts.obj" --features "$work/${mesh}_charts.json"
  for view in "$side1" "$side2"; do
    "$ctmap" render "$work/${mesh}_charts.obj" -o "docs/charts_${mesh}_${view}.png" --view "$view" --size 480 -q
  done
done <<'CHARTS'
cow chelsea.png front back
homer astronaut.png front back
bunny00 chelsea.png front back
bull astronaut.png top bottom
CHARTS
for case in homer:front elephant:three-quarter; do
  mesh=${case%%:*}; view=${case##*:}
  "$ctmap" starter-features "$(data "meshes/$mesh.off")" --image "$(data "images/astronaut.png")" -o "$work/${mesh}_patch.json"
  "$ctmap" map "$(data "meshes/$mesh.off")" "$work/${mesh}_patch.json" -o "$work/${mesh}_patch.obj" --quiet
  "$ctmap" check "$work/${mesh}_patch.obj" --features "$work/${mesh}_patch.json"
  for v in "$view" back; do
    "$ctmap" render "$work/${mesh}_patch.obj" -o "docs/charts_${mesh}_rest_$v.png" --view "$v" --size 480 -q
  done
done
