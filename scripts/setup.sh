#!/usr/bin/env bash
# The set-up command: dependencies, example data, build, and the main job on the shipped example.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/fetch_data.sh
bash scripts/build.sh build
./build/ctmap demo --out out/demo
