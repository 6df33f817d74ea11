#!/usr/bin/env bash
# `penumbra render` on hostile input and beyond its limits: each case exits with its documented
# code (docs/robustness.md), prints exactly one error line that says what is wrong, and leaves no
# output file behind. Usage: limits_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

# expect NAME EXIT_CODE PATTERN SCENE [ARGS...]: renders SCENE to $scratch/out.png with ARGS and
# checks the exit code, that stderr has exactly one line with "error" and that it matches the
# extended regular expression PATTERN, and that no output (or temporary) file was written.
# Runs with the environment the caller exported (used for the GL and EGL cases).
expect_failure() {
  local name=$1 code=$2 pattern=$3 scene=$4
  shift 4
  rm -f "$scratch"/out.png "$scratch"/.out.png.tmp*
  local output status
  output=$("$penumbra" render "$scene" -o "$scratch/out.png" "$@" 2>&1 >/dev/null)
  status=$?
  local error_lines
  error_lines=$(grep -c -i 'error' <<<"$output")
  if [[ $status -ne $code ]]; then
    fail "$name: exit $status, expected $code" "$output"
  elif [[ $error_lines -ne 1 ]]; then
    fail "$name: $error_lines error lines, expected exactly one" "$output"
  elif ! grep -i 'error' <<<"$output" | grep -Eq -- "$pattern"; then
    fail "$name: the error line does not match /$pattern/" "$output"
  elif compgen -G "$scratch/*out.png*" >/dev/null; then
    fail "$name: an output file was written" "$(ls -a "$scratch")"
  else
    pass "$name"
  fi
}

expect_success() {
  local name=$1 scene=$2
  shift 2
  rm -f "$scratch"/out.png
  local output status
  output=$("$penumbra" render "$scene" -o "$scratch/out.png" "$@" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne 0 ]]; then
    fail "$name: exit $status, expected 0" "$output"
  elif [[ ! -s $scratch/out.png ]]; then
    fail "$name: no output file" "$output"
  else
    pass "$name"
  fi
}

# A lit scene around one model; $1 is the model's path, $2 the scene's name.
scene_with_model() {
  cat >"$scratch/$2" <<SCENE
material panel
  emit 2 2 2
end
area_light panel
  pos1 -0.5 2 -0.5
  pos2  0.5 2 -0.5
  pos3  0.5 2  0.5
  pos4 -0.5 2  0.5
  at 0 0 0
  mat panel
end
camera main
  pos 0 1 3
  at 0 0.5 0
  screen_size 32 32
end
object $1
end
SCENE
  echo "$scratch/$2"
}

floor=$source_dir/scenes/assets/room.obj
good=$(scene_with_model "$floor" good.scene)
expect_success "a valid scene renders" "$good"

# --- GL limits and the command line -------------------------------------------------------------
expect_failure "width beyond the GL texture limit exits 4" 4 \
  "image size 100000x32 is outside what this GL implementation supports" "$good" --size 100000x32
expect_failure "height beyond the GL texture limit exits 4" 4 \
  "image size 32x100000 is outside" "$good" --size 32x100000
expect_failure "no VPLs exits 2" 2 "VPL count 0 is not a square number from 1 to" "$good" --vpls 0
expect_failure "too many VPLs exits 2" 2 "VPL count 4096 is not a square number" "$good" --vpls 4096
expect_failure "a VPL count that is not square exits 2" 2 "VPL count 3 is not a square" "$good" \
  --vpls 3
expect_failure "a negative VPL count exits 2" 2 "VPL count -16 is not a square" "$good" --vpls -16
# The grid's memory is checked before any allocation: 2048^3 voxels, three copies of one bit each
# (3072 MiB), the occupancy pyramid of the clear-light test (713 MiB) and the table of the boxes
# inside the voxels (512 MiB, a word per cell of 4^3 voxels; its pool is sized later).
expect_failure "a voxel grid too large for memory exits 2" 2 \
  "a voxel grid of 2048 x 2048 x 2048 needs 4297 MiB, more than the limit of 1024 MiB" "$good" \
  --voxel-resolution 2048

# --- scenes ----------------------------------------------------------------------------------------
: >"$scratch/empty.scene"
expect_failure "an empty scene exits 3" 3 "empty.scene: error: .*no area_light.*nothing would be lit" \
  "$scratch/empty.scene"
cat >"$scratch/dark.scene" <<SCENE
camera main
  pos 0 1 3
  at 0 0.5 0
  screen_size 32 32
end
object $floor
end
SCENE
expect_failure "a scene without lights exits 3" 3 "dark.scene: error: .*no area_light" \
  "$scratch/dark.scene"

# A scene file above the size limit is rejected before it is read; the sparse file takes no disk.
truncate -s 257M "$scratch/huge.scene"
expect_failure "a scene file above 256 MiB exits 3" 3 "huge.scene: error: .*limited to 256 MiB" \
  "$scratch/huge.scene"

# --- models ----------------------------------------------------------------------------------------
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n' >"$scratch/lines.obj"
expect_failure "a model with no triangles exits 3" 3 "lines.obj has no triangles" \
  "$(scene_with_model "$scratch/lines.obj" lines.scene)"

# Two triangles of zero area (a repeated corner, three points on a line) beside a proper one:
# they cover no pixel and render as nothing (docs/robustness.md).
printf 'v 0 0 0\nv 1 0 0\nv 0 0 1\nv 2 0 0\nf 1 2 3\nf 1 2 2\nf 1 2 4\n' >"$scratch/degenerate.obj"
expect_success "a model with degenerate triangles renders" \
  "$(scene_with_model "$scratch/degenerate.obj" degenerate.scene)"

printf 'v 0 0 0\nv nan 0 0\nv 0 0 1\nf 1 2 3\n' >"$scratch/nan.obj"
expect_failure "NaN in an OBJ exits 3 and names the file" 3 "nan.obj: vertex 1 has the non-finite" \
  "$(scene_with_model "$scratch/nan.obj" nan_obj.scene)"
# A binary PLY whose second vertex is a NaN bit pattern (0x7fc00000).
/usr/bin/python3 - "$scratch/nan.ply" <<'PY'
import struct, sys
header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
          b"property float y\nproperty float z\nelement face 1\n"
          b"property list uchar int vertex_indices\nend_header\n")
vertices = struct.pack("<3f", 0, 0, 0) + struct.pack("<I2f", 0x7FC00000, 0, 0) + struct.pack("<3f", 0, 0, 1)
open(sys.argv[1], "wb").write(header + vertices + struct.pack("<B3i", 3, 0, 1, 2))
PY
expect_failure "NaN in a binary PLY exits 3 and names the file" 3 "nan.ply: vertex 1 has the non-finite" \
  "$(scene_with_model "$scratch/nan.ply" nan_ply.scene)"

# The repository's bunny cut in its header, and cut in its faces.
bunny=$source_dir/scenes/assets/bunny.ply
head -c 200 "$bunny" >"$scratch/cut_header.ply"
expect_failure "a PLY cut in its header exits 3" 3 "cut_header.ply: the PLY header has no end_header" \
  "$(scene_with_model "$scratch/cut_header.ply" cut_header.scene)"
head -c $(($(stat -c %s "$bunny") - 1000)) "$bunny" >"$scratch/cut_faces.ply"
expect_failure "a PLY cut in its faces exits 3" 3 "cannot read model .*cut_faces.ply" \
  "$(scene_with_model "$scratch/cut_faces.ply" cut_faces.scene)"

truncate -s 2049M "$scratch/huge.ply"
expect_failure "a model file above 2 GiB exits 3" 3 "huge.ply is 2148532224 bytes; model files are limited" \
  "$(scene_with_model "$scratch/huge.ply" huge_model.scene)"

# --- GL and EGL ------------------------------------------------------------------------------------
# Mesa can be told to offer at most GL 3.3; the context then cannot be created.
MESA_GL_VERSION_OVERRIDE=3.3 MESA_GLSL_VERSION_OVERRIDE=330 \
  expect_failure "no GL 4.5 exits 4" 4 "OpenGL 4.5" "$good"
# libglvnd finds no EGL vendor library, as on a machine without any EGL driver.
__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json __EGL_VENDOR_LIBRARY_DIRS=/nonexistent \
  expect_failure "no EGL device exits 4" 4 "EGL" "$good"

# --- glTF scenes (docs/scene-format.md, `scene PATH`) ------------------------------------------
# Broken copies of the repository's glTF room, each given directly as the scene: one error line
# naming the glTF file, exit 3, no output.
gltf_room=$source_dir/scenes/gltf/blender_room.gltf
# broken_gltf NAME EDIT: a copy of the room as $scratch/NAME.gltf (its buffer a copy in $scratch)
# after the Python statement EDIT on its JSON `g` and its buffer bytes `b`.
broken_gltf() {
  /usr/bin/python3 - "$gltf_room" "$scratch/$1.gltf" "$2" <<'PYTHON'
import json, pathlib, struct, sys
source, target, edit = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
g = json.loads(source.read_text())
b = bytearray((source.parent / g["buffers"][0]["uri"]).read_bytes())
g["images"][0]["uri"] = str(source.parent / g["images"][0]["uri"])
exec(edit)
buffer = target.with_suffix(".bin")
buffer.write_bytes(b)
g["buffers"][0]["uri"] = g["buffers"][0].get("uri") and buffer.name
target.write_text(json.dumps(g))
PYTHON
  echo "$scratch/$1.gltf"
}
printf '{ "asset": { "version": ' >"$scratch/broken.gltf"
expect_failure "a glTF with broken JSON exits 3" 3 "broken\.gltf'?: broken JSON" "$scratch/broken.gltf"
missing_buffer=$(broken_gltf missing_buffer 'pass')
rm "$scratch/missing_buffer.bin"
expect_failure "a glTF whose buffer is missing exits 3" 3 "glTF '.*missing_buffer\.gltf'" \
  "$missing_buffer"
# The cube's positions (accessor 4) claim far more vertices than their buffer view holds.
expect_failure "a glTF accessor beyond its buffer exits 3" 3 "glTF '.*accessor\.gltf'" \
  "$(broken_gltf accessor 'g["accessors"][4]["count"] = 100000')"
nan_position='view = g["bufferViews"][g["accessors"][4]["bufferView"]]
b[view["byteOffset"]:view["byteOffset"] + 4] = struct.pack("<f", float("nan"))'
expect_failure "a glTF with a NaN position exits 3" 3 "vertex 0 has the non-finite position" \
  "$(broken_gltf nan "$nan_position")"
expect_failure "a glTF camera with zero aspect exits 3" 3 \
  "camera 'View': 'aspectRatio' must be a positive number, found 0" \
  "$(broken_gltf aspect 'g["cameras"][0]["perspective"]["aspectRatio"] = 0')"
# The room as scenes/gltf/blender_room.scene imports it: it renders, and the warnings list what
# the file holds that is not used.
room_output=$("$penumbra" render "$source_dir/scenes/gltf/blender_room.scene" --size 48x32 \
  --vpls 16 -o "$scratch/room.png" 2>&1 >/dev/null)
if [[ ! -s $scratch/room.png ]]; then
  fail "the glTF room renders" "$room_output"
elif [[ $(grep -c "warning: glTF .*blender_room.gltf: 1 " <<<"$room_output") -ne 6 ]]; then
  fail "the glTF room's warnings list the six features not used" "$room_output"
else
  pass "the glTF room renders and its warnings list the six features not used"
fi

# --- outputs ---------------------------------------------------------------------------------------
output_status() {
  local name=$1 pattern=$2 output_path=$3
  local output status
  output=$("$penumbra" render "$good" -o "$output_path" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne 5 ]]; then
    fail "$name: exit $status, expected 5" "$output"
  elif [[ $(grep -c -i 'error' <<<"$output") -ne 1 ]] || ! grep -Eq -- "$pattern" <<<"$output"; then
    fail "$name: expected one error line matching /$pattern/" "$output"
  elif [[ -e $output_path ]]; then
    fail "$name: the output exists" "$output"
  else
    pass "$name"
  fi
}
output_status "an output in a missing directory exits 5" "directory .*missing.* does not exist" \
  "$scratch/missing/out.png"
# /proc takes no new files, even from root (tests may run as root, where permission bits do not
# stop writes).
output_status "an output that cannot be created exits 5" "cannot save image /proc/penumbra-out.png" \
  /proc/penumbra-out.png

finish
