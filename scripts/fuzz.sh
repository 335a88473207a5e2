#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang, ASan + UBSan) in build-san (scripts/san_build.sh) and runs each for a
# bounded time on a scratch copy of its seed corpus (fuzz/corpus/<target>; the committed corpus is
# never grown). Fails if any target reports a crash, a sanitizer report, a leak, a time-out (an
# input over 5 s) or running out of memory (2 GB).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET (default 60)] [TARGET ...]   (fuzz/README.md)
set -euo pipefail
# Whatever ends the script early names itself, on stdout and stderr (CI shows a part of the output).
trap 'rc=$?; msg="fuzz: stopped at scripts/fuzz.sh line $LINENO (exit $rc): $BASH_COMMAND"; echo "$msg"; echo "$msg" >&2; exit $rc' ERR
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
if ! [[ $seconds =~ ^[0-9]+$ ]]; then
  echo "fuzz: SECONDS_PER_TARGET must be a whole number, not '$seconds'"; echo "fuzz: bad SECONDS_PER_TARGET" >&2
  exit 2
fi
all_targets=(fuzz_off fuzz_obj fuzz_ply fuzz_stl fuzz_textured_obj fuzz_features fuzz_pairs fuzz_image fuzz_glb fuzz_gltf)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
dir=${CTMAP_SAN_DIR:-build-san}

symbolizer=$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)

start=$SECONDS
# The one sanitizer build (scripts/san_build.sh; -O1 without NDEBUG: assertions stay on).
if ! bash scripts/san_build.sh fuzz_all; then
  echo "fuzz: building the fuzz targets in $dir failed"; echo "fuzz: build failed" >&2
  exit 1
fi
echo "fuzz: build took $((SECONDS - start)) s"

# One run folder per invocation, in the build tree: each target's corpus copy, log and artifacts.
runs="$dir/fuzz-runs/$(date +%Y%m%d-%H%M%S)"
mkdir -p "$runs"
ln -sfn "$(basename "$runs")" "$dir/fuzz-runs/latest"

max_len_of() {
  case $1 in
    fuzz_image | fuzz_glb | fuzz_gltf) echo 16384 ;;
    *) echo 8192 ;;
  esac
}

export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
[ -n "$symbolizer" ] && export ASAN_SYMBOLIZER_PATH="$symbolizer"

# CTMAP_FUZZ_KEEP_GOING=1: fork mode (one child at a time) that records every crash, time-out and
# out-of-memory input and keeps fuzzing, instead of stopping at the first; still fails if any.
keep_going=()
[ "${CTMAP_FUZZ_KEEP_GOING:-0}" = 1 ] && keep_going=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)

# CTMAP_FUZZ_SEED=N: a fixed libFuzzer seed, so a run (CI's) can be repeated exactly.
seed=()
[ -n "${CTMAP_FUZZ_SEED:-}" ] && seed=(-seed="$CTMAP_FUZZ_SEED")

# fuzz_one TARGET: the regression inputs, then the campaign, of one target; prints its lines and
# leaves its verdict (ok, failed or regressed) in $runs/TARGET/verdict.
fuzz_one() {
  local t=$1
  local exe="$dir/fuzz/$t" work="$runs/$t" log t0 rc artifacts n_artifacts execs cov result result_n= artifact
  mkdir -p "$work/corpus"
  cp fuzz/corpus/"$t"/* "$work/corpus/"
  log="$work/log.txt"
  mkdir -p "$work/tmp"  # the targets' input files (fuzz_common.h)
  t0=$SECONDS
  rc=0
  # First the inputs that once failed (fuzz/regressions/<target>): each must now pass.
  if [ -d "fuzz/regressions/$t" ]; then
    if ! TMPDIR="$PWD/$work/tmp" timeout --signal=KILL 120 "$exe" -timeout=5 -rss_limit_mb=2048 -artifact_prefix="$work/regression-" \
        fuzz/regressions/"$t"/* >"$work/regressions.txt" 2>&1; then
      echo "fuzz: $t fails on a regression input (fuzz/regressions/$t; $work/regressions.txt)"
      { grep -E '==ctmap-fuzz==|ERROR:|runtime error|Running:' "$work/regressions.txt" || true; } | tail -6 | sed 's/^/    /'
      echo regressed >"$work/verdict"
      return
    fi
  fi
  if [ "${CTMAP_FUZZ_REGRESSIONS_ONLY:-0}" = 1 ]; then
    local n_regressions=0
    [ ! -d "fuzz/regressions/$t" ] || n_regressions=$(find "fuzz/regressions/$t" -type f | wc -l)
    printf 'fuzz: %-18s regression inputs: %s passed\n' "$t" "$n_regressions"
    echo ok >"$work/verdict"
    return
  fi
  echo "fuzz: $t: ${seconds} s of fuzzing"
  # The outer timeout only guards against libFuzzer itself hanging.
  TMPDIR="$PWD/$work/tmp" timeout --signal=KILL $((seconds + 120)) "$exe" "$work/corpus" -max_total_time="$seconds" -timeout=5 \
    -rss_limit_mb=2048 -max_len="$(max_len_of "$t")" -detect_leaks=1 -print_final_stats=1 \
    -artifact_prefix="$work/" ${seed[@]+"${seed[@]}"} ${keep_going[@]+"${keep_going[@]}"} >"$log" 2>&1 || rc=$?
  artifacts=$(find "$work" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' \
    -o -name 'oom-*' \) | sort)
  n_artifacts=$(printf '%s' "$artifacts" | grep -c . || true)
  [ "$rc" -ne 0 ] || [ "$n_artifacts" -eq 0 ] || rc=1
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | head -1 || true)
  [ -n "$execs" ] || execs=$(grep -oE '^#[0-9]+' "$log" | tail -1 | tr -d '#' || true)
  [ ${#keep_going[@]} -eq 0 ] || result_n=" x$n_artifacts"
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || true)
  if [ "$rc" -eq 0 ]; then
    result=ok
  else
    if grep -q 'ERROR: libFuzzer: timeout' "$log"; then result=timeout
    elif grep -qE 'ERROR: libFuzzer: (out-of-memory|malloc limit)' "$log"; then result=out-of-memory
    elif grep -q 'ERROR: LeakSanitizer' "$log"; then result=leak
    elif grep -q 'ERROR: AddressSanitizer' "$log"; then
      result="asan:$({ grep -m1 -oE 'ERROR: AddressSanitizer: [a-z-]+' "$log" || true; } | awk '{print $3}')"
    elif grep -q 'runtime error:' "$log"; then result=ubsan
    elif grep -q '==ctmap-fuzz==' "$log"; then result=contract
    elif [ "$rc" -eq 137 ]; then result=hung
    else result="crash(rc=$rc)"
    fi
    result+=${result_n:-}
  fi
  artifact=$(printf '%s' "$artifacts" | head -1)
  printf 'fuzz: %-18s %-14s execs=%-9s cov=%-6s %3ss%s\n' "$t" "$result" "${execs:-?}" "${cov:-?}" \
    "$((SECONDS - t0))" "${artifact:+  reproducer: $artifact}"
  if [ "$result" != ok ]; then
    echo "---- $t: the report ($log)"
    # (no match, as for a target the outer timeout killed, and head closing the pipe early must
    # not end the script under `set -e -o pipefail`: the summary below still has to be printed)
    { grep -E '==ctmap-fuzz==|ERROR:|runtime error|^ *#[0-9]+ 0x' "$log" || true; } | sed -n '1,12p' | cut -c1-220 | sed 's/^/    /'
    [ "$result" != hung ] || tail -3 "$log" | sed 's/^/    /'
  fi
  if [ "$result" = ok ]; then echo ok >"$work/verdict"; else echo failed >"$work/verdict"; fi
}

# CTMAP_FUZZ_JOBS targets at a time (default: one per core), each target's lines printed as it ends.
for t in "${targets[@]}"; do
  [ -x "$dir/fuzz/$t" ] || { echo "fuzz: no target $t (targets: ${all_targets[*]})" ; echo "fuzz: no target $t" >&2; exit 1; }
done
jobs=${CTMAP_FUZZ_JOBS:-$(nproc)}
declare -A job_of=()
finish_one() {
  local pid
  wait -n -p pid ${!job_of[@]} || true
  cat "$runs/${job_of[$pid]}.out"
  unset "job_of[$pid]"
}
for t in "${targets[@]}"; do
  while [ ${#job_of[@]} -ge "$jobs" ]; do finish_one; done
  fuzz_one "$t" >"$runs/$t.out" 2>&1 &
  job_of[$!]=$t
done
while [ ${#job_of[@]} -gt 0 ]; do finish_one; done
failed=()
regressed=()
for t in "${targets[@]}"; do
  verdict=$(cat "$runs/$t/verdict" 2>/dev/null || echo failed)
  [ "$verdict" = ok ] || failed+=("$t")
  [ "$verdict" != regressed ] || regressed+=("$t")
done
if [ "${CTMAP_FUZZ_REGRESSIONS_ONLY:-0}" = 1 ]; then
  if [ ${#failed[@]} -gt 0 ]; then
    echo "fuzz: FAILED regression inputs: ${failed[*]}"; echo "fuzz: FAILED regression inputs: ${failed[*]}" >&2
    exit 1
  fi
  exit 0
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, $((SECONDS - start)) s in all; logs in $runs"
# CTMAP_FUZZ_REPORT_ONLY=1: what the campaign finds is printed but does not fail the run; a
# regression input that fails still does (for exploring by hand; the test command gates on every finding).
if [ ${#failed[@]} -gt 0 ] && [ "${CTMAP_FUZZ_REPORT_ONLY:-0}" = 1 ] && [ ${#regressed[@]} -eq 0 ]; then
  echo "fuzz: FINDINGS (reported, not failing): ${failed[*]} (reproduce: $dir/fuzz/TARGET REPRODUCER)" >&2
  exit 0
fi
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]} (reproduce: $dir/fuzz/TARGET REPRODUCER)" >&2
  exit 1
fi
