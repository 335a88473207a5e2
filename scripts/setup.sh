#!/usr/bin/env bash
# The set-up command: dependencies, example data, the program, and the main job on the shipped
# example. (The tests and the Python module are built by scripts/test.sh or scripts/build.sh.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/fetch_data.sh
CTMAP_BUILD_TARGETS=ctmap bash scripts/build.sh build
./build/ctmap demo --out out/demo
