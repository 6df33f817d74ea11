#!/usr/bin/env bash
# `penumbra bench`: the JSON it writes (docs/bench.md) for both modes on a fixed view and along an
# orbit, and its errors (exit codes, no JSON written). Timings are only checked to be present and
# consistent, never against a bound. Usage: bench_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

# The Cornell box with the bunny at 32x32 with 16 VPLs: every pass runs, in seconds.
bench() {
  "$penumbra" bench "$source_dir/scenes/cornell_bunny.scene" --size 32x32 --vpls 16 "$@" \
    >"$scratch/out" 2>"$scratch/err"
}

# json_check FILE PYTHON_EXPRESSION: the expression, over the parsed file `d`, is true.
json_check() {
  /usr/bin/python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if ($2) else 1)" "$1"
}

# --no-reuse: every measured frame traces its visibility, as it would without the warm-up frame.
bench --frames 2 --warmup 1 --no-reuse --json "$scratch/fixed.json"
check "both modes on a fixed view exit 0" test $? -eq 0
check "schema, timing method and both modes" json_check "$scratch/fixed.json" \
  "d['schema'] == 'penumbra-bench-2' and d['timing_method'] in ('cpu-after-glfinish', 'gl-timer-queries') and set(d['modes']) == {'hierarchical', 'naive'}"
check "the hierarchical gather is timed per level and summed" json_check "$scratch/fixed.json" \
  "all(abs(r['gather_ms'] - sum(v for k, v in r['pass_ms'].items() if k.startswith('gather/'))) < 1e-9 for r in d['modes']['hierarchical']['frame_records'])"
check "the naive gather is its one pass" json_check "$scratch/fixed.json" \
  "all(r['gather_ms'] == r['pass_ms']['gather'] for r in d['modes']['naive']['frame_records'])"
check "a record per measured frame, all at the scene's camera" json_check "$scratch/fixed.json" \
  "all(len(m['frame_records']) == 2 and all(r['orbit_degrees'] == 0 and r['scene_frame'] == 0 for r in m['frame_records']) for m in d['modes'].values())"
check "the samples per level add up in every record" json_check "$scratch/fixed.json" \
  "all(sum(l['samples'] for l in r['statistics']['levels']) == r['statistics']['samples_gathered'] for r in d['modes']['hierarchical']['frame_records'])"
check "the shadow rays per level add up, against the naive mode's pixels x VPLs" json_check "$scratch/fixed.json" \
  "all(sum(l['shadow_rays'] for l in s['levels']) == s['shadow_rays'] > 0 and s['naive_shadow_rays'] == s['full_resolution_samples'] * s['vpls_per_light'] * d['lights'] for s in [r['statistics'] for r in d['modes']['hierarchical']['frame_records']])"
check "the comparison holds the speedups and the error" json_check "$scratch/fixed.json" \
  "d['comparison']['ideal_speedup'] > 1 and d['comparison']['relative_mse'] >= 0"
check "with --no-reuse no frame reuses, and every level's figures are consistent" json_check "$scratch/fixed.json" \
  "all(not s['visibility_reused'] and s['gather_vpls_kept'] == 0 and s['visibility_masked_texels'] >= s['visibility_traced_texels'] > 0 and 0 <= s['share_without_rays'] < 1 and abs(s['shadow_rays_per_lit_pixel'] * s['full_resolution_samples'] - s['shadow_rays']) < 1e-6 * s['shadow_rays'] and all(l['visibility_masked_texels'] >= l['visibility_traced_texels'] and abs(l['shadow_rays_per_lit_pixel'] * s['full_resolution_samples'] - l['shadow_rays']) < 1e-6 * max(l['shadow_rays'], 1) for l in s['levels']) for s in [r['statistics'] for r in d['modes']['hierarchical']['frame_records']])"

# Without --no-reuse, the measured frames of a fixed view keep the warm-up frame's visibility.
bench --frames 2 --warmup 1 --modes hierarchical --json "$scratch/reused.json"
check "a fixed view reuses visibility after its first frame" json_check "$scratch/reused.json" \
  "all(s['visibility_reused'] and s['shadow_rays'] == 0 and s['visibility_traced_texels'] == 0 and s['visibility_masked_texels'] > 0 and s['share_without_rays'] == 1 for s in [r['statistics'] for r in d['modes']['hierarchical']['frame_records']])"
check "the summary says the visibility was reused" grep -q "visibility: reused from the last frame" "$scratch/out"
check "a fixed view keeps the gathered sums of every light (none has a video)" json_check "$scratch/reused.json" \
  "all(s['gather_vpls_kept'] == s['vpls_per_light'] * d['lights'] > 0 for s in [r['statistics'] for r in d['modes']['hierarchical']['frame_records']])"
check "the summary says the sums were kept" grep -q "gather: the sums of 16 VPLs kept from the last frame" "$scratch/out"

bench --frames 3 --warmup 1 --orbit 12 --modes hierarchical --json "$scratch/orbit.json"
check "an orbit exits 0" test $? -eq 0
check "an orbit of 12 frames puts 3 frames at -30, 0 and 30 degrees" json_check "$scratch/orbit.json" \
  "[r['orbit_degrees'] for r in d['modes']['hierarchical']['frame_records']] == [-30, 0, 30]"
check "the scene's time advances a frame per measured frame" json_check "$scratch/orbit.json" \
  "[r['scene_frame'] for r in d['modes']['hierarchical']['frame_records']] == [0, 1, 2] and d['orbit'] == 12"
check "the summary names the orbit" grep -q "along an orbit of 12 frames" "$scratch/out"
check "along an orbit no frame reuses its masks, the first measured one (its camera a step past the warm-up's) included" json_check "$scratch/orbit.json" \
  "not any(r['statistics']['visibility_reused'] for r in d['modes']['hierarchical']['frame_records'])"
check "along an orbit of the still box every frame keeps the voxel grid" json_check "$scratch/orbit.json" \
  "all(r['statistics']['visibility_structure_kept'] for r in d['modes']['hierarchical']['frame_records'])"
check "the summary says the grid was kept" grep -q "kept from the last frame" "$scratch/out"
bench --frames 2 --warmup 1 --orbit 12 --modes hierarchical --no-reuse --json "$scratch/orbit-no-reuse.json"
check "along an orbit with --no-reuse every frame builds its grid" json_check "$scratch/orbit-no-reuse.json" \
  "not any(r['statistics']['visibility_structure_kept'] or r['statistics']['reuse_visibility'] for r in d['modes']['hierarchical']['frame_records'])"

bench --modes fast --json "$scratch/bad.json"
check "an unknown mode exits 2" test $? -eq 2
check "an unknown mode names it" grep -q "unknown mode 'fast'" "$scratch/err"
check "an unknown mode writes no JSON" test ! -e "$scratch/bad.json"

bench --orbit -1
check "a negative orbit exits 2" test $? -eq 2

bench --json "$scratch/missing/out.json"
check "a JSON file in a missing directory exits 5" test $? -eq 5
check "a JSON file in a missing directory is named" grep -q "missing" "$scratch/err"

finish
