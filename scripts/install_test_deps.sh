#!/usr/bin/env bash
# What the tests need beyond the main job's packages (scripts/install_deps.sh): Debian's Blender,
# for the add-on's headless test (tests/blender/test_addon.py, issue 44). The test command runs
# this; the set-up command does not. Does nothing when it is present.
set -euo pipefail
packages=(blender)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "test dependencies: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "test dependencies: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
