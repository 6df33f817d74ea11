#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time and prints its executions.
# Usage: fuzz/run-fuzzers.sh BUILD_DIR SECONDS [SEED]
# SEED 0 (the default) lets libFuzzer pick a random seed; any other value fixes the sequence of
# mutations, so that a run from the same corpus repeats (CI uses 1).
# Each target starts from its seed corpus (fuzz/corpus/<target>, never modified) plus what earlier
# runs in BUILD_DIR found; findings go to BUILD_DIR/fuzz-artifacts/<target>/. Exits non-zero when
# any target found a crash, a leak, a timeout or an out-of-memory input.
set -uo pipefail

build=$1
seconds=$2
seed=${3:-0}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
targets=(scene_parser model_loader gltf_scene image_loader)

# One input may take a while on a loaded 2-core machine (assimp and OpenImageIO are slow under
# ASan), but never this long. The memory limit leaves room for the largest image loadImage
# accepts (2 GiB for 8192x8192 pixels) plus the sanitizers' own.
per_input_timeout=25
rss_limit_mb=4096

# Leaks inside third-party libraries that we cannot free (each explained in the file).
export LSAN_OPTIONS=suppressions=$source_dir/tests/lsan.supp

failed=0
summary=()
for target in "${targets[@]}"; do
  work=$build/fuzz-corpus/$target
  artifacts=$build/fuzz-artifacts/$target
  log=$build/fuzz-logs/$target.log
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  echo "fuzz: $target for $seconds s (log: $log)"
  "$build/fuzz/fuzz_$target" "$work" "$source_dir/fuzz/corpus/$target" \
    -max_total_time="$seconds" -seed="$seed" -timeout="$per_input_timeout" -rss_limit_mb="$rss_limit_mb" \
    -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1
  status=$?
  executions=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$')
  result=ok
  if [[ $status -ne 0 ]]; then
    result="FOUND A PROBLEM (exit $status): $(ls "$artifacts" | tr '\n' ' ')"
    grep -m3 -E 'ERROR|SUMMARY|failure' "$log"
    failed=1
  fi
  summary+=("$(printf '%-13s %9s executions %6s/s  %s' "$target" "${executions:-?}" "${rate:-?}" "$result")")
done

echo "fuzz: executions per target in $seconds s"
printf '  %s\n' "${summary[@]}"
exit $failed
