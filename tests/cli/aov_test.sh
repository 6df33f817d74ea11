#!/usr/bin/env bash
# `penumbra render --aov`: one multi-layer EXR holding the radiance and the named debug views,
# each layer equal to the single `--debug-view` output of the same frame, with the camera matrices
# and the settings in its header; bad uses exit 2 and write nothing.
# Usage: aov_test.sh PATH_TO_PENUMBRA SOURCE_DIR
source "$(dirname "$0")/harness.sh" "$@"

scene=$source_dir/scenes/shadow_box.scene
# Small and cheap; hierarchical, so that the levels view exists.
render() {
  "$penumbra" render "$scene" --size 48x48 --vpls 16 --voxel-resolution 32 "$@" 2>"$scratch/log"
}

layers=albedo,normal,depth,levels
if render --aov "$layers" -o "$scratch/aov.exr" -o "$scratch/aov.png"; then
  pass "render --aov exits 0"
else
  fail "render --aov exits 0" "$(cat "$scratch/log")"
fi
render -o "$scratch/radiance.exr"
for view in ${layers//,/ }; do
  render --debug-view "$view" -o "$scratch/$view.exr"
done

check_layers() {
  /usr/bin/python3 - "$scratch" "$layers" <<'EOF'
import json
import sys

import numpy as np
import OpenImageIO as oiio

scratch, layers = sys.argv[1], sys.argv[2].split(",")


def read(path):
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(format="float")
    image.close()
    return spec, pixels


spec, pixels = read(f"{scratch}/aov.exr")
names = list(spec.channelnames)
# OpenEXR stores the channels sorted by name, so they are looked up by name.
expected = ["R", "G", "B"] + [f"{layer}.{c}" for layer in layers for c in "RGB"]
assert sorted(names) == sorted(expected), names


def layer(prefix):
    return pixels[:, :, [names.index(prefix + c) for c in "RGB"]]


_, radiance = read(f"{scratch}/radiance.exr")
# Exact: the same frame, rendered by the same code, stored as the same floats.
assert np.array_equal(layer(""), radiance[:, :, 0:3]), "radiance differs"
for name in layers:
    _, single = read(f"{scratch}/{name}.exr")
    assert np.array_equal(layer(name + "."), single[:, :, 0:3]), f"{name} differs"
    assert single[:, :, 0:3].any(), f"{name} is black, so comparing it proves nothing"

view = np.array(spec.getattribute("worldtocamera"), dtype=np.float64).reshape(4, 4)
# The camera at (0, 2.2, 3.4): the view matrix (row-vector layout) takes it to the origin.
eye = np.array([0.0, 2.2, 3.4, 1.0]) @ view
assert np.allclose(eye[:3], 0.0, atol=1e-5), eye
assert spec.getattribute("worldtoscreen") is not None
settings = json.loads(spec.getattribute("penumbra:settings"))
assert settings["mode"] == "hierarchical" and settings["vpls_per_light"] == 16, settings
assert settings["shadows"]["voxel_resolution"] == 32, settings
assert spec.getattribute("penumbra:layers") == ",".join(layers)
camera = json.loads(spec.getattribute("penumbra:camera"))
assert camera["fovy_degrees"] == 45, camera
EOF
}
check "the layers equal the single debug views, and the header has the camera and settings" \
  check_layers
check "a PNG output beside the EXR holds the radiance" test -s "$scratch/aov.png"

# expect_usage_error NAME MESSAGE ARGS...: exit 2, the message, and no output file.
expect_usage_error() {
  local name=$1 message=$2
  shift 2
  rm -f "$scratch/bad.exr"
  render "$@" -o "$scratch/bad.exr"
  local code=$?
  if [[ $code -eq 2 ]] && grep -qF -- "$message" "$scratch/log" && [[ ! -e $scratch/bad.exr ]]; then
    pass "$name"
  else
    fail "$name" "exit $code; $(cat "$scratch/log")"
  fi
}
expect_usage_error "an unknown layer is a usage error" "unknown debug view 'colour'" \
  --aov albedo,colour
expect_usage_error "a layer smaller than the image is a usage error" \
  "--aov worklist-1: the view is" --aov worklist-1 --coarsest 8
expect_usage_error "--aov needs a GPU mode" "--aov needs a GPU mode" --aov albedo \
  --mode reference --spp 1
rm -f "$scratch/bad.png"
"$penumbra" render "$scene" --size 48x48 --aov albedo -o "$scratch/bad.png" 2>"$scratch/log"
code=$?
if [[ $code -eq 2 ]] && grep -qF "add one" "$scratch/log" && [[ ! -e $scratch/bad.png ]]; then
  pass "--aov without an .exr output is a usage error"
else
  fail "--aov without an .exr output is a usage error" "exit $code; $(cat "$scratch/log")"
fi

finish
