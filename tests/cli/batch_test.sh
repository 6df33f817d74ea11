#!/usr/bin/env bash
# docs/batch.md's promise: a frame range split over processes gives the frames of one run. The
# animated, video-lit room renders frames 0 to 5 in one process, and again as 0:2 and 3:5 in two
# processes at once; every frame must be the same, bit for bit. (The page's join into a video
# uses the ffmpeg program, which is not a dependency.) Usage: batch_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

# Small and cheap: 48x48, 16 VPLs per light; shadows and the hierarchy stay on.
render() {
  "$penumbra" render "$source_dir/scenes/tv_room.scene" --size 48x48 --vpls 16 "$@"
}

mkdir "$scratch/one" "$scratch/split"
render --frames 0:5 -o "$scratch/one/frame_%04d.exr" 2>"$scratch/log_one"
check "one run of frames 0:5 exits 0" test $? -eq 0
render --frames 0:2 -o "$scratch/split/frame_%04d.exr" 2>"$scratch/log_first" &
first=$!
render --frames 3:5 -o "$scratch/split/frame_%04d.exr" 2>"$scratch/log_second" &
second=$!
wait $first
check "the first half exits 0" test $? -eq 0
wait $second
check "the second half exits 0" test $? -eq 0

check "both runs wrote frames 0 to 5" test \
  "$(cd "$scratch/one" && ls)" = "$(cd "$scratch/split" && ls)" -a \
  "$(cd "$scratch/one" && ls | wc -l)" -eq 6
for frame in 0000 0001 0002 0003 0004 0005; do
  "$penumbra" compare "$scratch/split/frame_$frame.exr" "$scratch/one/frame_$frame.exr" \
    --metric max --tol 0 >"$scratch/compare" 2>&1
  check "frame $frame of the split run is the one run's" test $? -eq 0
done
# The animation and the video move: equal frames would make the comparisons above weak.
"$penumbra" compare "$scratch/one/frame_0000.exr" "$scratch/one/frame_0005.exr" --metric max \
  --tol 0 >"$scratch/compare" 2>&1
check "the frames differ from each other" test $? -eq 1

finish
