#!/usr/bin/env bash
# Runs every measurement behind docs/performance.md, then draws its figures and writes the page.
# Usage: bench/performance.sh PENUMBRA (run by `make performance`). The results (one JSON file
# per run, and the printed summary beside it) go to bench/results/; bench/performance.py turns
# them into docs/images/perf-*.png and docs/performance.md. About 25 minutes on the project's
# 2-core machine; run it on an otherwise idle machine, since the times are wall-clock.
set -euo pipefail

penumbra=$(realpath "$1")
cd "$(dirname "$0")/.."
# The dragon scenes read the Stanford dragon from beside the repository (bench/README.md).
for mesh in stanford_dragon_full.ply stanford_dragon_res2.ply; do
  if [[ ! -f ../shared/assets/meshes/$mesh ]]; then
    echo "performance: ../shared/assets/meshes/$mesh is missing; bench/README.md says how to get it" >&2
    exit 3
  fi
done

results=bench/results
rm -rf "$results"
mkdir -p "$results"

# Every run traces visibility in every frame (--no-reuse): the fixed-camera runs' measured frames
# would otherwise keep the warm-up frame's visibility, and the figures are of the method's work.
run() {
  local name=$1
  shift
  set -- "$@" --no-reuse
  echo "performance: $name: penumbra bench $*"
  echo "penumbra bench $* --json $results/$name.json" >"$results/$name.txt"
  # Other work on the machine slows every pass: the page reports the load seen by the runs.
  echo "load before: $(cut -d ' ' -f 1 /proc/loadavg)" >>"$results/$name.txt"
  "$penumbra" bench "$@" --json "$results/$name.json" >>"$results/$name.txt" 2>/dev/null
  echo "load after: $(cut -d ' ' -f 1 /proc/loadavg)" >>"$results/$name.txt"
}

# Frames of naive per-pixel visibility take tens of seconds: their first frame is measured (its
# one-off shader compilation is under a second of it), with no warm-up frame.

# Along a camera path: the thesis's kind of scene (video light, full-resolution dragon) and the
# bunny in the same room. 12 frames 1/96 turn apart: an arc of 45 degrees through the camera.
run orbit-tv-dragon bench/tv_dragon.scene --size 512x512 --orbit 96 --frames 12 --warmup 1 \
  --modes hierarchical
run orbit-tv-bunny scenes/tv_room.scene --size 512x512 --orbit 96 --frames 12 --warmup 1 \
  --modes hierarchical

# Naive against hierarchical, for the lighting alone and with visibility.
run versus-lighting bench/tv_dragon.scene --size 512x512 --no-shadows --frames 3 --warmup 1
run versus-visibility bench/tv_dragon.scene --size 512x512 --frames 1 --warmup 0

# The normal threshold: quality (against naive) and time.
for threshold in 0.025 0.05 0.1 0.2 0.4 0.8; do
  run "normal-$threshold" bench/tv_dragon.scene --size 512x512 --no-shadows \
    --normal-threshold "$threshold" --frames 3 --warmup 1
done

# Scaling: VPLs per light (one light), with shadows.
for vpls in 64 144 256 576 1024; do
  run "vpls-$vpls" scenes/cornell_bunny.scene --size 256x256 --vpls "$vpls" --frames 1 --warmup 0
done

# Scaling: resolution, both modes without shadows, the hierarchy with shadows.
for side in 256 512 1024 2048; do
  run "size-$side" scenes/cornell_bunny.scene --size "${side}x$side" --no-shadows --frames 3 \
    --warmup 1
  run "size-shadows-$side" scenes/cornell_bunny.scene --size "${side}x$side" --frames 1 \
    --warmup 1 --modes hierarchical
done

# Scaling: triangles, the same Cornell box with the bunny and the dragon at two resolutions.
run triangles-bunny scenes/cornell_bunny.scene --size 1024x1024 --frames 2 --warmup 1 \
  --modes hierarchical
run triangles-dragon-202k bench/cornell_dragon_res2.scene --size 1024x1024 --frames 2 --warmup 1 \
  --modes hierarchical
run triangles-dragon-871k bench/cornell_dragon.scene --size 1024x1024 --frames 2 --warmup 1 \
  --modes hierarchical

# Scaling: the voxel grid.
for resolution in 64 128 192 256 384; do
  run "voxels-$resolution" scenes/cornell_bunny.scene --size 512x512 \
    --voxel-shape equal --voxel-resolution "$resolution" --frames 2 --warmup 1 --modes hierarchical
done

/usr/bin/python3 bench/performance.py "$results"
