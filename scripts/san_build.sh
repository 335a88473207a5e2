#!/usr/bin/env bash
# The one sanitizer build (build-san): clang with AddressSanitizer + UndefinedBehaviorSanitizer, and
# libFuzzer's coverage instrumentation on the readers (CTMAP_FUZZ), with assertions on (no NDEBUG:
# CGAL's and Eigen's preconditions are checked). -O1 with line tables only (ASan's reports name file
# and line; full debug information costs compile time): -O0 compiles twice as fast but runs the
# bad-input suite six times slower. The bad-input suite (scripts/test.sh) and the fuzz targets
# (scripts/fuzz.sh) both run from it.
# Usage: scripts/san_build.sh TARGET...   (e.g. fuzz_all, ctmap, ctmap_input_tests)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${CTMAP_SAN_DIR:-build-san}
# Debian's clang-14 (scripts/install_deps.sh: clang-14, libclang-rt-14-dev, llvm-14).
cxx=${CTMAP_FUZZ_CXX:-$(command -v clang++ || command -v clang++-14 || true)}
if [ -z "$cxx" ]; then
  echo "san_build: no clang++ (install clang-14 and libclang-rt-14-dev: scripts/install_deps.sh)" >&2
  exit 1
fi
# The generator and the compiler are chosen at the first configure only (changing the compiler of
# an existing build tree makes CMake drop its cache).
first=()
if [ ! -f "$dir/CMakeCache.txt" ]; then
  command -v ninja >/dev/null && first=(-G Ninja)
  first+=(-DCMAKE_CXX_COMPILER="$cxx")
fi
mkdir -p "$dir"
if ! cmake -S . -B "$dir" ${first[@]+"${first[@]}"} -DCTMAP_FUZZ=ON -DCTMAP_BUILD_TESTS=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" >"$dir/configure.log" 2>&1; then
  echo "san_build: configuring $dir failed:" >&2; tail -20 "$dir/configure.log" >&2
  exit 1
fi
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$dir" -j2 ${targets[@]+"${targets[@]}"}
