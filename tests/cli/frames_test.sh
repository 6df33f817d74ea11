#!/usr/bin/env bash
# `penumbra render --frames`: image sequences through a frame-number pattern, MP4 output, bad
# ranges and patterns (exit 2, nothing written), and clear errors for missing or damaged videos.
# Usage: frames_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

# The files in a directory, one per line, sorted.
listing() {
  (cd "$1" && find . -mindepth 1 | sort)
}

# A light showing VIDEO, seen from the front, over a floor. Small and cheap to render.
write_scene() {
  local file=$1 video=$2
  cat >"$file" <<EOF
material screen
  emit 2 2 2
  tex $video
end
area_light tv
  pos1 -1 0 -1
  pos2 1 0 -1
  pos3 1 1 -1
  pos4 -1 1 -1
  at 0 0.5 0
  mat screen
end
camera c
  pos 0 0.5 2
  at 0 0.5 0
  screen_size 32 32
end
EOF
}

# render ARGS...: penumbra render with the cheap settings every case here uses.
render() {
  "$penumbra" render --mode naive --vpls 1 --no-shadows "$@"
}

scene=$scratch/tv.scene
write_scene "$scene" "$source_dir/scenes/assets/tv_screen_128x72_30fps.mp4"

# One render to an image sequence and a video: exactly the three numbered files, and the video
# under its name only when complete.
mkdir "$scratch/sequence" "$scratch/video"
render "$scene" --frames 0:2 -o "$scratch/sequence/out_%04d.png" -o "$scratch/video/clip.mp4" \
  2>"$scratch/log"
check "--frames 0:2 exits 0" test $? -eq 0
check "--frames 0:2 writes exactly 3 files" \
  test "$(listing "$scratch/sequence")" = "$(printf './out_0000.png\n./out_0001.png\n./out_0002.png')"
# Different video frames light the scene differently.
check "frames differ" bash -c '! cmp -s "$1/out_0000.png" "$1/out_0002.png"' _ "$scratch/sequence"
check "the video is the only file" test "$(listing "$scratch/video")" = "./clip.mp4"

# --stats-json: an array with each frame's statistics over a range, one object for one frame.
render "$scene" --frames 1:3 -o "$scratch/stats_%d.png" --stats-json "$scratch/range.json" \
  2>"$scratch/log"
check "--stats-json over a range writes frames 1 to 3" /usr/bin/python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if [f['frame'] for f in d] == [1, 2, 3] and all(f['mode'] == 'naive' for f in d) else 1)
" "$scratch/range.json"
render "$scene" --frame 4 -o "$scratch/stats.png" --stats-json "$scratch/one.json" 2>"$scratch/log"
check "--stats-json for one frame writes its object" /usr/bin/python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if d['frame'] == 4 and d['mode'] == 'naive' else 1)
" "$scratch/one.json"

# One frame through a pattern.
mkdir "$scratch/single"
render "$scene" --frame 7 -o "$scratch/single/frame_%02d.png" 2>"$scratch/log"
check "--frame 7 fills the pattern" test -f "$scratch/single/frame_07.png"

# Usage errors: exit 2 and nothing written.
# expect_usage_error NAME PATTERN ARGS...: exit 2, stderr matching PATTERN, $scratch/empty empty.
expect_usage_error() {
  local name=$1 pattern=$2
  shift 2
  rm -rf "$scratch/empty" && mkdir "$scratch/empty"
  render "$scene" "$@" 2>"$scratch/log"
  local status=$?
  if [[ $status -ne 2 ]]; then
    fail "$name: exit $status, expected 2" "$(cat "$scratch/log")"
  elif ! grep -Eq -- "$pattern" "$scratch/log"; then
    fail "$name: stderr does not match /$pattern/" "$(cat "$scratch/log")"
  elif [[ -n $(listing "$scratch/empty") ]]; then
    fail "$name: wrote $(listing "$scratch/empty")"
  else
    pass "$name"
  fi
}
expect_usage_error "reversed range" "--frames: expected FIRST:LAST.*found '2:1'" \
  --frames 2:1 -o "$scratch/empty/out_%04d.png"
expect_usage_error "negative range" "found '-1:3'" --frames -1:3 -o "$scratch/empty/out_%04d.png"
expect_usage_error "range that is no range" "found '0-3'" --frames 0-3 -o "$scratch/empty/out_%d.png"
expect_usage_error "several frames to one image" "needs a frame-number pattern" \
  --frames 0:2 -o "$scratch/empty/out.png"
expect_usage_error "pattern without an integer conversion" "one frame-number conversion" \
  --frames 0:2 -o "$scratch/empty/out_%s.png"
expect_usage_error "pattern with two conversions" "one frame-number conversion" \
  --frames 0:2 -o "$scratch/empty/out_%d_%d.png"
expect_usage_error "odd-sized video" "even width and height" \
  --frames 0:2 --size 33x32 -o "$scratch/empty/out.mp4"
expect_usage_error "--frame with --frames" "excludes" \
  --frame 1 --frames 0:2 -o "$scratch/empty/out_%d.png"

# The video reads back as a video texture.
write_scene "$scratch/replay.scene" "$scratch/video/clip.mp4"
render "$scratch/replay.scene" --frame 3 -o "$scratch/replay.png" 2>"$scratch/log"
check "the video plays as a light's texture" test $? -eq 0

# Missing or damaged videos: exit 3 (bad input) with the scene location and the file's name.
write_scene "$scratch/missing.scene" "$scratch/missing.mp4"
render "$scratch/missing.scene" -o "$scratch/missing.png" 2>"$scratch/log"
status=$?
check "missing video exits 3" test $status -eq 3
check "missing video: the message names the scene line and the file" \
  grep -Eq "missing.scene:[0-9]+.*missing.mp4.*not found" "$scratch/log"
check "missing video: no output" test ! -e "$scratch/missing.png"

head -c 300 "$scratch/video/clip.mp4" >"$scratch/damaged.mp4"
write_scene "$scratch/damaged.scene" "$scratch/damaged.mp4"
render "$scratch/damaged.scene" -o "$scratch/damaged.png" 2>"$scratch/log"
status=$?
check "damaged video exits 3" test $status -eq 3
check "damaged video: the message names the file and the scene line" \
  grep -Eq "damaged.scene:[0-9]+.*damaged.mp4" "$scratch/log"

finish
