#!/usr/bin/env bash
# bench/gpu-run (docs/bench.md, "Figures from a real GPU"): a --demo-only pack of the built binary
# runs its --quick benches on llvmpipe with every packed library loaded from the pack, reports that
# this is no real GPU (exit 6), and fails when a packed library is missing from the pack.
# Usage: gpu_run_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

pack=$scratch/gpu-run
if "$source_dir/bench/gpu-run" pack --binary "$penumbra" --demo-only "$pack" >"$scratch/pack.log" 2>&1; then
  pass "pack exits 0"
else
  fail "pack exits 0" "$(cat "$scratch/pack.log")"
fi

# ldd of the packed binary, given the pack's folder alone: every library resolves into the pack
# but glibc's (Debian's libc6), which must be the target's.
outside=$(LD_LIBRARY_PATH=$pack/lib ldd "$pack/bin/penumbra" |
  awk -v lib="$pack/lib/" '$2 == "=>" && index($3, lib) != 1 { print $3 }' |
  while read -r path; do
    if ! dpkg -S "$path" 2>/dev/null | grep -q '^libc6:'; then echo "$path"; fi
  done)
if [[ -z $outside ]]; then
  pass "ldd resolves every library but glibc's from the pack"
else
  fail "ldd resolves every library but glibc's from the pack" "$outside"
fi
missing=""
for name in libEGL.so.1 libOpenGL.so.0 libGLdispatch.so.0; do
  [[ -f $pack/lib/$name ]] || missing+=" $name"
done
if [[ -z $missing ]]; then
  pass "the pack holds glvnd's loaders"
else
  fail "the pack holds glvnd's loaders" "missing:$missing"
fi

# The scenes keep their relative paths inside the pack: the runner reads them from there.
check "the pack holds the demo and its assets" test -f "$pack/repo/scenes/demo.scene" -a \
  -f "$pack/repo/scenes/assets/room.mtl" -a -f "$pack/repo/scenes/assets/tv_frame150.png"

# Run from a copy's own folder, away from the source tree.
output=$scratch/out
(cd "$scratch" && "$pack/gpu-run" run --quick "$output") >"$scratch/run.log" 2>&1
status=$?
log=$(cat "$scratch/run.log")
if [[ $status -eq 6 ]]; then
  pass "run --quick on llvmpipe exits 6 (not a real GPU)"
else
  fail "run --quick on llvmpipe exits 6 (not a real GPU)" "exit $status; $log"
fi
check "run prints penumbra --version" grep -q "^penumbra [0-9]" <<<"$log"
check "run checks the loaded libraries" grep -q "packed libraries that were loaded came from the pack" <<<"$log"
check "run warns loudly of CPU timing" grep -q "NOT A REAL GPU MEASUREMENT: quick-demo-64 was timed with \"cpu-after-glfinish\"" <<<"$log"
for name in quick-demo-64 quick-demo-64-noshadows; do
  if /usr/bin/python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(d["width"] != 64 or d["timing_method"] != "cpu-after-glfinish")' "$output/$name.json" 2>/dev/null; then
    pass "$name.json is a 64x64 bench"
  else
    fail "$name.json is a 64x64 bench" "$(cat "$output/$name.err" 2>/dev/null)"
  fi
done
check "the log is written" test -s "$output/gpu-run.log"

# A library missing from the pack is loaded from the system: the check must catch it.
rm "$pack/lib/libepoxy.so.0"
(cd "$scratch" && "$pack/gpu-run" run --quick "$scratch/out-stray") >"$scratch/stray.log" 2>&1
status=$?
if [[ $status -eq 1 ]] && grep -q "LIBRARY CHECK FAILED: packed libepoxy.so.0 was loaded from" "$scratch/stray.log"; then
  pass "a packed library loaded from the system fails the run"
else
  fail "a packed library loaded from the system fails the run" "exit $status; $(cat "$scratch/stray.log")"
fi

"$pack/gpu-run" run 2>/dev/null
check "run without an OUTPUT folder exits 2" test $? -eq 2

finish
