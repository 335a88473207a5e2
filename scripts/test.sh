#!/usr/bin/env bash
# The test command (README; .ci/run calls it). Usage: scripts/test.sh [--long]
#   default: the release build and the main suite (CTest, without the label `long`), the bad-input
#            suite again under ASan + UBSan, and the readers under libFuzzer from a fixed seed
#            (CTMAP_FUZZ_SECONDS per target, default 20); any finding fails the command.
#   --long:  the release build and the long cases only (CTest label `long`: the large meshes and
#            the many-set sweeps, each with a short sibling in the main suite).
# Every step prints its time, and a table of them at the end. Benchmarks: bench/run.
set -euo pipefail
cd "$(dirname "$0")/.."
long=0
case "${1:-}" in
  "") ;;
  --long) long=1 ;;
  *) echo "usage: scripts/test.sh [--long]" >&2; exit 2 ;;
esac

names=()
times=()
started=$SECONDS
summary() {
  local rc=$?
  echo "== test command: step times"
  local i
  for i in "${!names[@]}"; do printf '   %-44s %5s s\n' "${names[$i]}" "${times[$i]}"; done
  printf '   %-44s %5s s\n' "total" "$((SECONDS - started))"
  if [ "$rc" -eq 0 ]; then echo "== test command: every step passed"; else echo "== test command: FAILED (exit $rc)"; fi
}
trap summary EXIT
# step NAME COMMAND...: runs one step, prints and records its seconds (also when it fails).
step() {
  local name=$1
  shift
  echo "== $name"
  local t0=$SECONDS rc=0
  "$@" || rc=$?
  names+=("$name")
  times+=("$((SECONDS - t0))")
  echo "== $name: $((SECONDS - t0)) s"
  return $rc
}
in_dir() { (cd "$1" && shift && "$@"); }

step "dependencies (scripts/install_deps.sh)" bash scripts/install_deps.sh
# Debian's Blender for the add-on's headless test (tests/blender), not part of the set-up.
step "test dependencies (install_deps.sh blender)" bash scripts/install_deps.sh blender
step "example data (scripts/fetch_data.sh)" bash scripts/fetch_data.sh
step "release build (build/)" bash scripts/build.sh build -DCTMAP_BUILD_TESTS=ON
# three.js and playwright-core for the viewer test (tests/web), exactly as package-lock.json pins them.
step "npm ci (tests/web)" in_dir tests/web npm ci --no-audit --no-fund
if [ $long -eq 1 ]; then
  step "long suite (ctest -L long)" in_dir build ctest --output-on-failure -j2 -L long --timeout 1800
  exit 0
fi
step "main suite (ctest -LE long)" in_dir build ctest --output-on-failure -j2 -LE long --timeout 600
# One clang build with ASan + UBSan (scripts/san_build.sh) for the bad-input suite and the fuzz
# targets, building only what those two steps run.
step "sanitizer build (build-san/)" bash scripts/san_build.sh ctmap ctmap_input_tests fuzz_all
# Render's CLI test matches 'BadInput' by name but drives Mesa's llvmpipe, whose own allocations
# LeakSanitizer reports: it runs in the release build only.
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
step "bad-input suite under ASan + UBSan" in_dir build-san \
  ctest --output-on-failure -j2 -R 'BadInput|RoundTrip' -E '^Render' --timeout 1200
unset ASAN_OPTIONS UBSAN_OPTIONS
# The readers under libFuzzer (fuzz/README.md): per target, first the inputs that once failed
# (fuzz/regressions), then a short campaign from a fixed seed. Any finding fails the command.
# Longer runs: scripts/fuzz.sh 600.
step "fuzzing, ${CTMAP_FUZZ_SECONDS:-20} s per target (scripts/fuzz.sh)" \
  env CTMAP_FUZZ_SEED="${CTMAP_FUZZ_SEED:-1}" bash scripts/fuzz.sh "${CTMAP_FUZZ_SECONDS:-20}"
