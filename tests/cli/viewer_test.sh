#!/usr/bin/env bash
# `penumbra view` under Xvfb: it opens a window with a GL 4.5 core context, renders the demo for a
# few frames, saves a screenshot that is not uniform, and exits 0 without GL errors; the
# automation flags are checked before any window opens. Usage: viewer_test.sh PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

# fail_with_log NAME: a failure with the viewer's output.
fail_with_log() {
  fail "$1" "$(cat "$scratch/log" 2>/dev/null)"
}

# Xvfb's screen is larger than every window here. 16 VPLs per light and no shadows keep a frame
# of llvmpipe short; the settings do not change what this test checks.
view() {
  xvfb-run -a -s "-screen 0 1024x768x24" \
    "$penumbra" view "$source_dir/scenes/demo.scene" --size 256x256 --vpls 16 --no-shadows "$@" \
    >"$scratch/log" 2>&1
}

# The window is the picture (--size) and the panel beside it, 400 pixels wide (docs/viewer.md).
panel_width=400

# screenshot_varies FILE: a screenshot of the 256x256 picture and the panel whose pixel values are
# not all the same.
screenshot_varies() {
  /usr/bin/python3 - "$1" "$panel_width" <<'PYTHON'
import sys
import OpenImageIO as oiio
pixels = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)
expected = (256, 256 + int(sys.argv[2]))
if pixels is None or pixels.shape[:2] != expected:
    sys.exit(f"{sys.argv[1]}: expected a {expected[1]}x{expected[0]} window")
if pixels[..., :3].std() < 0.01:
    sys.exit(f"{sys.argv[1]}: the picture is uniform")
PYTHON
}

# Pixel values vary a lot where the window shows both the panel and the picture; a blank or
# single-colour window fails.
shot=$scratch/shot.png
if view --frames 5 --screenshot "$shot" --exit; then
  pass "5 frames of the demo exit 0"
else
  fail_with_log "5 frames of the demo exit 0"
fi
if grep -q "4.5 (Core Profile)" "$scratch/log"; then
  pass "GLX gives a 4.5 core context"
else
  fail_with_log "GLX gives a 4.5 core context"
fi
# Hot reload reads the source tree's shaders while it is there (the installed binary's own
# copies are tested in tests/package/installed_test.sh).
if grep -qF "view: shaders read from $source_dir/shaders (F5 reloads them)" "$scratch/log"; then
  pass "the viewer says it reads the source tree's shaders"
else
  fail_with_log "the viewer says it reads the source tree's shaders"
fi
if grep -q "view: 5 frames at 256x256" "$scratch/log"; then
  pass "the summary counts 5 frames"
else
  fail_with_log "the summary counts 5 frames"
fi
if [[ -s $shot ]] && screenshot_varies "$shot"; then
  pass "the screenshot is not empty"
else
  fail_with_log "the screenshot is not empty"
fi

# The picture is whole from the first frame: the left 256x256 of the window is the image `render`
# makes with the same settings, not covered by the panel or the help (shown at start).
if view --frames 1 --screenshot "$scratch/first.png" --exit &&
  "$penumbra" render "$source_dir/scenes/demo.scene" --size 256x256 --vpls 16 --no-shadows \
    -o "$scratch/rendered.png" 2>>"$scratch/log" &&
  /usr/bin/python3 - "$scratch/first.png" "$scratch/rendered.png" <<'PYTHON' >>"$scratch/log" 2>&1
import sys
import numpy
import OpenImageIO as oiio
window = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.UINT8)[:, :256, :3].astype(int)
rendered = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.UINT8)[..., :3].astype(int)
# Both are 8-bit sRGB of the same radiance. The window's is rounded to 8 bits by the display
# pass, then decoded to linear and encoded again when saved: each rounding is at most half a
# code, so the two can differ by one code.
difference = numpy.abs(window - rendered).max()
print(f"largest difference between the picture and the rendered image: {difference} codes")
sys.exit(0 if difference <= 1 else 1)
PYTHON
then
  pass "the first frame shows the whole picture beside the panel"
else
  fail_with_log "the first frame shows the whole picture beside the panel"
fi

# --orbit turns the camera every frame after the first: by a whole turn with --orbit 1, so that
# the second frame shows the first frame's view again; by a quarter with --orbit 4, so that the
# third looks at the demo from behind. share_changed A B prints the share of the pictures'
# pixels that differ by more than one code (the window's own rounding, as above).
share_changed() {
  /usr/bin/python3 - "$1" "$2" <<'PYTHON'
import sys
import numpy
import OpenImageIO as oiio
a = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.UINT8)[:, :256, :3].astype(int)
b = oiio.ImageBuf(sys.argv[2]).get_pixels(oiio.UINT8)[..., :3].astype(int)
print((numpy.abs(a - b).max(axis=2) > 1).mean())
PYTHON
}
if view --frames 2 --orbit 1 --screenshot "$scratch/whole_turn.png" --exit &&
  grep -q "view: 2 frames at 256x256, the camera turning 1/1 of a turn a frame" "$scratch/log"; then
  changed=$(share_changed "$scratch/whole_turn.png" "$scratch/rendered.png")
  # A turn by 2 pi in float leaves the eye a few ulps from where it was, which can move an edge
  # across a pixel centre here and there: at most 0.5% of the pixels.
  check "a whole turn a frame comes back to the first view ($changed changed)" \
    /usr/bin/python3 -c "import sys; sys.exit(0 if $changed <= 0.005 else 1)"
else
  fail_with_log "view --orbit 1 runs and says so"
fi
if view --frames 3 --orbit 4 --screenshot "$scratch/half_turn.png" --exit; then
  changed=$(share_changed "$scratch/half_turn.png" "$scratch/rendered.png")
  # Seen from behind, the room's walls and objects sit elsewhere in most of the picture.
  check "two quarter turns show another view ($changed changed)" \
    /usr/bin/python3 -c "import sys; sys.exit(0 if $changed >= 0.2 else 1)"
else
  fail_with_log "view --orbit 4 runs"
fi

# Other display kinds: integer texture through a palette, and a scalar through the colour map
# with its range read back from the picture.
for arguments in "--debug-view worklist --level 1" "--debug-view depth"; do
  # shellcheck disable=SC2086
  if view --frames 2 --no-help --screenshot "$scratch/other.png" --exit $arguments &&
    screenshot_varies "$scratch/other.png"; then
    pass "view $arguments"
  else
    fail_with_log "view $arguments"
  fi
done

# Every view of the registry (the names `view --help` lists, docs/viewer.md) renders in a frame
# that has every pass (hierarchical, shadows, indirect light): its picture differs from the
# radiance's, which a view the frame lacked would fall back to.
every_pass=(--size 64x64 --vpls 16 --coarsest 8 --voxel-resolution 32 --indirect
  --indirect-vpls 16 --frames 1 --no-help --exit)
names=$("$penumbra" view --help | /usr/bin/python3 -c '
import re, sys
line = next(l for l in sys.stdin if "--debug-view" in l)
print(" ".join(name.replace("[-N]", "") for name in re.split(r",\s*", line.split(": ", 1)[1].strip())))')
picture() {
  /usr/bin/python3 -c '
import sys
import OpenImageIO as oiio
pixels = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)
sys.stdout.buffer.write(pixels[:, :64].tobytes())' "$1"
}
xvfb-run -a -s "-screen 0 1024x768x24" "$penumbra" view "$source_dir/scenes/demo.scene" \
  "${every_pass[@]}" --screenshot "$scratch/radiance.png" >"$scratch/log" 2>&1
check "the registry lists views" test "$(wc -w <<<"$names")" -gt 20
for name in $names; do
  [[ $name == radiance ]] && continue
  if xvfb-run -a -s "-screen 0 1024x768x24" "$penumbra" view "$source_dir/scenes/demo.scene" \
    "${every_pass[@]}" --debug-view "$name" --screenshot "$scratch/view.png" \
    >"$scratch/log" 2>&1 && ! cmp -s <(picture "$scratch/radiance.png") <(picture "$scratch/view.png"); then
    pass "view --debug-view $name renders"
  else
    fail_with_log "view --debug-view $name renders"
  fi
done

# expect_exit [--windowed] NAME CODE PATTERN ARGS...: `penumbra view` on the demo with ARGS exits
# CODE with a line of output that matches PATTERN; --windowed runs it under Xvfb, for the cases
# that open the window. The viewer's own status is kept in a file: on a loaded machine xvfb-run
# sometimes fails to remove its temporary directory after a quick exit and then exits 5 itself.
expect_exit() {
  local launcher=()
  if [[ $1 == --windowed ]]; then
    launcher=(xvfb-run -a -s "-screen 0 1024x768x24")
    shift
  fi
  local name=$1 code=$2 pattern=$3
  shift 3
  "${launcher[@]}" bash -c '"$@"; echo $? >"$0"' "$scratch/status" \
    "$penumbra" view "$source_dir/scenes/demo.scene" "$@" >"$scratch/log" 2>&1
  local status
  status=$(cat "$scratch/status")
  if [[ $status -eq $code ]] && grep -Eq -- "$pattern" "$scratch/log"; then
    pass "$name"
  else
    echo "exit $status, expected $code and /$pattern/"
    fail_with_log "$name"
  fi
}

# A GL error during the run (the test-only hook of docs/cli.md) exits 1.
PENUMBRA_TEST_GL_ERROR=1 expect_exit --windowed "a GL error exits 1" 1 "the GL driver reported" \
  --size 64x64 --vpls 16 --no-shadows --frames 1 --exit
# Settings the renderer rejects while the window is open: with --exit, a usage error.
expect_exit --windowed "rejected settings exit 2" 2 "shadows support up to 1024" \
  --size 64x64 --vpls 1024 --frames 1 --exit

# The cases below open no window.
expect_exit "--exit needs --frames" 2 "requires --frames" --exit
expect_exit "--screenshot needs --frames" 2 "requires --frames" --screenshot "$scratch/a.png"
expect_exit "a screenshot format that is not 8-bit" 2 "expected .png or .jpg" \
  --frames 1 --screenshot "$scratch/a.exr" --exit
expect_exit "a screenshot directory that does not exist" 5 "does not exist" \
  --frames 1 --screenshot "$scratch/missing/a.png" --exit
expect_exit "an unknown view" 2 "unknown view 'nope'; expected one of: radiance" \
  --debug-view nope
expect_exit "a bad size" 2 "expected WIDTHxHEIGHT" --size 0x5
expect_exit "an orbit of no frames" 2 "--orbit: Value 0 not in range" --orbit 0
DISPLAY= expect_exit "no display" 4 "needs a display" --frames 1 --exit
[[ ! -e $scratch/a.png && ! -e $scratch/a.exr ]] && pass "failures write no screenshot" ||
  fail_with_log "failures write no screenshot"

finish
