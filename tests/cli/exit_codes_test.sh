#!/usr/bin/env bash
# docs/cli.md's exit codes, each for every command it applies to: the commands share one mapping
# (src/app/command_failure.h), so the same failure gives the same code whichever command meets
# it. `view`'s cases that need a window (0 and 1) are in viewer_test.sh, which runs under Xvfb.
# Usage: exit_codes_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

scene=$source_dir/scenes/cornell_bunny.scene
image=$source_dir/tests/data/images/reference.exr
size=(--size 32x32)
small=("${size[@]}" --vpls 16)

# expect_exit NAME CODE PATTERN ARGS...: `penumbra ARGS` exits CODE, and a line of its output
# (standard error and output) matches the extended regular expression PATTERN.
expect_exit() {
  local name=$1 code=$2 pattern=$3
  shift 3
  local errors status
  errors=$("$penumbra" "$@" 2>&1)
  status=$?
  if [[ $status -ne $code ]]; then
    fail "$name: exit $status, expected $code" "$errors"
  elif ! grep -Eq -- "$pattern" <<<"$errors"; then
    fail "$name: stderr does not match /$pattern/" "$errors"
  else
    pass "$name"
  fi
}

# no_file NAME PATH: nothing was written at PATH.
no_file() {
  check "$1" test ! -e "$2"
}

# --- 0: success ------------------------------------------------------------------------------------
expect_exit "render: success exits 0" 0 "" render "$scene" "${small[@]}" -o "$scratch/ok.exr"
expect_exit "bench: success exits 0" 0 "" bench "$scene" "${small[@]}" --frames 1 --warmup 0 \
  --modes naive
expect_exit "compare: images within tolerance exit 0" 0 "" compare "$image" "$image" --tol 0

# --- 1: a failed check -----------------------------------------------------------------------------
expect_exit "compare: over tolerance exits 1" 1 "> tolerance 0: FAIL" compare "$image" \
  "$source_dir/tests/data/images/close.exr" --metric rmse --tol 0
# PENUMBRA_TEST_GL_ERROR=1 (test-only, docs/cli.md) issues one invalid GL call as the context
# starts: the run must not succeed, nor write its outputs.
PENUMBRA_TEST_GL_ERROR=1 expect_exit "render: a GL error exits 1" 1 \
  "^penumbra: error: the GL driver reported [0-9]+ errors? \(printed above\)$" \
  render "$scene" "${small[@]}" -o "$scratch/gl_error.exr"
no_file "render: a GL error writes no image" "$scratch/gl_error.exr"
PENUMBRA_TEST_GL_ERROR=1 expect_exit "bench: a GL error exits 1" 1 \
  "^penumbra: error: the GL driver reported [0-9]+ errors? \(printed above\)$" \
  bench "$scene" "${small[@]}" --frames 1 --warmup 0 --modes naive --json "$scratch/gl_error.json"
no_file "bench: a GL error writes no JSON" "$scratch/gl_error.json"
PENUMBRA_TEST_GL_ERROR=1 expect_exit "render: the hook's call is reported as a GL error" 1 \
  "^GL error [a-z]+: " render "$scene" "${small[@]}" -o "$scratch/gl_error.exr"

# --- 2: the command line ---------------------------------------------------------------------------
# Each command with the arguments it requires, so that the unknown option is the one error.
expect_exit "render: an unknown option exits 2" 2 "^penumbra: error: .*--colour" \
  render "$scene" -o "$scratch/bad.exr" --colour red
expect_exit "bench: an unknown option exits 2" 2 "^penumbra: error: .*--colour" bench --colour red
expect_exit "view: an unknown option exits 2" 2 "^penumbra: error: .*--colour" view --colour red
expect_exit "compare: an unknown option exits 2" 2 "^penumbra: error: .*--colour" \
  compare "$image" "$image" --colour red
expect_exit "render: settings out of range exit 2" 2 "^penumbra: error: .*VPL count 3" \
  render "$scene" "${size[@]}" --vpls 3 -o "$scratch/bad.exr"
expect_exit "bench: settings out of range exit 2" 2 "^penumbra: error: .*VPL count 3" \
  bench "$scene" "${size[@]}" --vpls 3
expect_exit "render: a light proximity threshold of 0 exits 2" 2 \
  "^penumbra: error: .*light proximity threshold 0.* must be a positive finite number" \
  render "$scene" "${size[@]}" --light-proximity-threshold 0 -o "$scratch/bad.exr"
no_file "render: a bad light proximity threshold writes no image" "$scratch/bad.exr"

# --- 3: an input that cannot be used ---------------------------------------------------------------
missing=$scratch/missing.scene
expect_exit "render: a missing scene exits 3" 3 "^$missing: error: scene file not found$" \
  render "$missing" -o "$scratch/missing.exr"
for command in bench view; do
  expect_exit "$command: a missing scene exits 3" 3 "^$missing: error: scene file not found$" \
    "$command" "$missing"
done
expect_exit "compare: a missing image exits 3" 3 "^penumbra: error: .*missing.exr" \
  compare "$scratch/missing.exr" "$image"

# --- 4: no usable GL -------------------------------------------------------------------------------
# Mesa can be told to offer at most GL 3.3; the context then cannot be created.
MESA_GL_VERSION_OVERRIDE=3.3 MESA_GLSL_VERSION_OVERRIDE=330 expect_exit \
  "render: no GL 4.5 exits 4" 4 "OpenGL 4.5" render "$scene" "${small[@]}" -o "$scratch/no_gl.exr"
MESA_GL_VERSION_OVERRIDE=3.3 MESA_GLSL_VERSION_OVERRIDE=330 expect_exit \
  "bench: no GL 4.5 exits 4" 4 "OpenGL 4.5" bench "$scene" "${small[@]}"
# A shader folder (PENUMBRA_SHADER_DIR, a shader developer's) whose naive gather renamed a
# uniform the renderer sets: the setter names the program and the uniform (src/gl/program.h).
cp -r "$source_dir/shaders" "$scratch/shaders"
sed -i 's/eyePosition/eyeRenamed/g' "$scratch/shaders/gather_naive.comp"
PENUMBRA_SHADER_DIR=$scratch/shaders expect_exit "render: a uniform the shader lacks exits 4" 4 \
  '^penumbra: error: program gather_naive.comp has no active uniform "eyePosition"' \
  render "$scene" "${small[@]}" --mode naive -o "$scratch/renamed.exr"
no_file "render: a uniform the shader lacks writes no image" "$scratch/renamed.exr"
# The viewer's GL comes with its window: without a display there is none.
env -u DISPLAY -u WAYLAND_DISPLAY "$penumbra" view "$scene" --frames 1 --exit >/dev/null \
  2>"$scratch/view.log"
check "view: no display exits 4" test $? -eq 4

# --- 5: an output that cannot be written -----------------------------------------------------------
nowhere=$scratch/no/such/directory
expect_exit "render: an output in a missing directory exits 5" 5 "does not exist" \
  render "$scene" "${small[@]}" -o "$nowhere/out.exr"
expect_exit "bench: a JSON file in a missing directory exits 5" 5 "does not exist" \
  bench "$scene" "${small[@]}" --frames 1 --warmup 0 --json "$nowhere/out.json"
expect_exit "compare: an error image in a missing directory exits 5" 5 "cannot write" \
  compare "$image" "$image" --error-image "$nowhere/errors.png"
expect_exit "view: a screenshot in a missing directory exits 5" 5 "does not exist" \
  view "$scene" --frames 1 --screenshot "$nowhere/shot.png" --exit

# --- 130: interrupted ------------------------------------------------------------------------------
# The reference renderer stops at Ctrl-C (SIGINT) between tiles: sent once it has started (its
# first progress line), the run exits 130 and writes nothing.
"$penumbra" render "$scene" --mode reference --spp 4096 --size 64x64 \
  -o "$scratch/interrupted.exr" 2>"$scratch/interrupt.log" &
renderer=$!
for _ in $(seq 200); do
  grep -q "reference" "$scratch/interrupt.log" 2>/dev/null && break
  sleep 0.1
done
kill -INT "$renderer"
wait "$renderer"
status=$?
if [[ $status -eq 130 ]] && grep -q "^penumbra: error: interrupted" "$scratch/interrupt.log"; then
  pass "render: an interrupted run exits 130"
else
  fail "render: an interrupted run exits 130: exit $status" "$(cat "$scratch/interrupt.log")"
fi
no_file "render: an interrupted run writes nothing" "$scratch/interrupted.exr"

finish
