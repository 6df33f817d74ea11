#!/usr/bin/env bash
# The conventions every command shares (docs/cli.md): exit codes for missing input and bad
# arguments, one error style for the option parser's errors and ours, enum options by name only,
# and the progress of `render --frames` on the GPU modes. Usage: command_line_test.sh PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

scene=$source_dir/scenes/cornell_bunny.scene
image=$source_dir/tests/data/images/reference.exr

# expect NAME CODE PATTERN COMMAND ARGS...: `penumbra COMMAND ARGS` exits CODE and its standard
# error is exactly one line, which matches the extended regular expression PATTERN.
expect() {
  local name=$1 code=$2 pattern=$3
  shift 3
  local errors status
  errors=$("$penumbra" "$@" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne $code ]]; then
    fail "$name: exit $status, expected $code" "$errors"
  elif [[ $(wc -l <<<"$errors") -ne 1 ]]; then
    fail "$name: expected one line on stderr" "$errors"
  elif ! grep -Eq -- "$pattern" <<<"$errors"; then
    fail "$name: stderr does not match /$pattern/" "$errors"
  else
    pass "$name"
  fi
}

# --- a missing or unusable input is bad input (3) for every command ------------------------------
missing=$scratch/missing.scene
expect "render: a missing scene exits 3" 3 "^$missing: error: scene file not found$" \
  render "$missing" -o "$scratch/out.png"
expect "view: a missing scene exits 3" 3 "^$missing: error: scene file not found$" \
  view "$missing" --frames 1 --exit
expect "bench: a missing scene exits 3" 3 "^$missing: error: scene file not found$" \
  bench "$missing"
expect "compare: a missing image exits 3" 3 "^penumbra: error: .*missing.exr" \
  compare "$scratch/missing.exr" "$image"
expect "compare: a missing mask scene exits 3" 3 "^penumbra: error: --mask-emitters: .*not found" \
  compare "$image" "$image" --mask-emitters "$missing"
expect "render: a directory as the scene exits 3 and says so" 3 \
  "^$scratch: error: is a directory, not a scene file$" render "$scratch" -o "$scratch/out.png"

# A damaged PNG: libpng's own message is not printed beside ours, and ours is one line.
head -c 100 "$source_dir/scenes/assets/tv_frame150.png" >"$scratch/cut.png"
expect "compare: a damaged PNG is one error line" 3 \
  "^penumbra: error: cannot read image .*cut.png: .*Read error" compare "$scratch/cut.png" "$image"
cat >"$scratch/textured.scene" <<SCENE
material screen
  emit 1 1 1
  tex cut.png
end
area_light screen
  pos1 0 0 0
  pos2 1 0 0
  pos3 1 1 0
  pos4 0 1 0
  mat screen
end
SCENE
expect "render: a damaged texture is one error line at its tex value" 3 \
  "^$scratch/textured.scene:3:7: error: cannot read image .*cut.png: .*Read error" \
  render "$scratch/textured.scene" -o "$scratch/out.png"

# --- bad arguments are usage errors (2), in our one style ----------------------------------------
expect "render: a value that is no number exits 2" 2 \
  "^penumbra: error: Could not convert: --exposure = abc" \
  render "$scene" --exposure abc -o "$scratch/out.png"
expect "view: a value that is no number exits 2" 2 "^penumbra: error: .*--level" \
  view "$scene" --level abc
expect "bench: a value that is no number exits 2" 2 "^penumbra: error: .*--frames" \
  bench "$scene" --frames abc
expect "compare: a value that is no number exits 2" 2 "^penumbra: error: .*--tol" \
  compare "$image" "$image" --tol abc
expect "an unknown option exits 2" 2 "^penumbra: error: .*--colour" \
  render "$scene" --colour red -o "$scratch/out.png"
expect "a missing command exits 2" 2 "^penumbra: error: A subcommand is required"
expect "our own usage errors share the style" 2 "^penumbra: error: --spp must be at least 1$" \
  render "$scene" --mode reference --spp 0 -o "$scratch/out.png"
expect "render --aov's usage errors share the style" 2 \
  "^penumbra: error: --aov needs a GPU mode \(hierarchical or naive\)$" \
  render "$scene" --mode reference --aov albedo -o "$scratch/out.exr"
expect "render: an unknown --aov layer is a usage error in the style" 2 \
  "^penumbra: error: unknown debug view 'colour'; expected one of:" \
  render "$scene" --quiet --size 16x16 --vpls 1 --aov albedo,colour -o "$scratch/out.exr"
"$penumbra" --version >"$scratch/version" 2>"$scratch/log"
check "--version exits 0 and prints the version on standard output" \
  grep -Eq "^penumbra [0-9]+\.[0-9]+\.[0-9]+$" "$scratch/version"
check "--version writes nothing on standard error" test ! -s "$scratch/log"

# --- enum options: names only ---------------------------------------------------------------------
for command in render view bench; do
  help=$("$penumbra" "$command" --help)
  if grep -Eq -- '->|OR \{|ENUM' <<<"$help"; then
    fail "$command --help shows names only" "$(grep -E -- '->|OR \{|ENUM' <<<"$help")"
  else
    pass "$command --help shows names only"
  fi
done
check "render --help lists the modes and the default" \
  grep -Eq -- "--mode hierarchical\|naive\|reference\|reference-vpl=hierarchical" \
  <<<"$("$penumbra" render --help)"
check "render --help lists the voxel grids and the default" \
  grep -Eq -- "--voxel-grid world\|screen=world" <<<"$("$penumbra" render --help)"
check "render --help lists the visibility methods and the default" \
  grep -Eq -- "--visibility voxels\|bvh=voxels" <<<"$("$penumbra" render --help)"
expect "render: an unknown visibility method exits 2" 2 "^penumbra: error: --visibility: rays not in" \
  render "$scene" --visibility rays -o "$scratch/out.png"
"$penumbra" render "$scene" --size 16x16 --vpls 4 --visibility BVH --stats-json "$scratch/bvh.json" \
  -o "$scratch/bvh.png" 2>"$scratch/log"
check "--visibility bvh is recorded with the BVH's memory" /usr/bin/python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if d['shadows']['visibility'] == 'bvh' and d['visibility_bytes'] > 0 else 1)" \
  "$scratch/bvh.json"
check "compare --help lists the metrics and the default" \
  grep -Eq -- "--metric rmse\|relmse\|psnr\|mae\|max\|ssim\|flip=rmse" <<<"$("$penumbra" compare --help)"
expect "render: a mode by number exits 2" 2 "^penumbra: error: --mode: 2 not in" \
  render "$scene" --mode 2 -o "$scratch/out.png"
expect "view: a mode by number exits 2" 2 "^penumbra: error: --mode: 1 not in" \
  view "$scene" --mode 1
expect "bench: a traversal by number exits 2" 2 "^penumbra: error: --traversal: 0 not in" \
  bench "$scene" --traversal 0
expect "render: a visibility measure by number exits 2" 2 \
  "^penumbra: error: --visibility-measure: 1 not in" \
  render "$scene" --visibility-measure 1 -o "$scratch/out.png"
expect "compare: a metric by number exits 2" 2 "^penumbra: error: --metric: 0 not in" \
  compare "$image" "$image" --metric 0
"$penumbra" render "$scene" --size 16x16 --vpls 1 --mode NAIVE --voxel-grid Screen --traversal UNIFORM \
  --stats-json "$scratch/names.json" -o "$scratch/names.png" 2>"$scratch/log"
check "names are accepted in any case" /usr/bin/python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if d['mode'] == 'naive' else 1)" "$scratch/names.json"

# --- progress of a frame range on the GPU modes ---------------------------------------------------
# on_terminal COMMAND...: runs it with standard error on a pseudo-terminal (util-linux `script`)
# and prints what the terminal showed.
on_terminal() {
  script -qec "$(printf '%q ' "$@") >/dev/null" /dev/null
}
frames=(render "$scene" --size 16x16 --vpls 1 --no-shadows --mode naive --frames 0:2
  -o "$scratch/frame_%d.png")
shown=$(on_terminal "$penumbra" "${frames[@]}")
check "a frame range shows its progress on a terminal" \
  grep -Eq "naive \[#+\] 100%  frame 2, 3 of 3  elapsed [0-9]+s  ETA 0s" <<<"$shown"
shown=$(on_terminal "$penumbra" "${frames[@]}" --quiet)
check "--quiet shows no progress" bash -c '! grep -q "ETA" <<<"$1"' _ "$shown"
check "--quiet shows no summary" bash -c '! grep -q "rendered" <<<"$1"' _ "$shown"
"$penumbra" "${frames[@]}" 2>"$scratch/log"
check "a frame range off a terminal exits 0" test $? -eq 0
check "a frame range off a terminal prints no progress" \
  bash -c '! grep -Eq "ETA|of 3" "$1"' _ "$scratch/log"

finish
