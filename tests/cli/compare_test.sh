#!/usr/bin/env bash
# `penumbra compare` end to end: metrics, tolerances and exit codes, the emitter mask, the error
# image and the JSON report. Usage: compare_test.sh PATH_TO_PENUMBRA SOURCE_DIR
# The images come from tests/data/images/make_images.py (see there for their values).
source "$(dirname "$0")/harness.sh" "$@"
images=$source_dir/tests/data/images

# expect NAME EXIT_CODE PATTERN -- ARGS...: runs `penumbra compare ARGS`, checks the exit code and
# that stdout+stderr match the extended regular expression PATTERN (empty: no check).
expect() {
  local name=$1 code=$2 pattern=$3
  shift 4
  local output status
  output=$("$penumbra" compare "$@" 2>&1)
  status=$?
  if [[ $status -ne $code ]]; then
    fail "$name: exit $status, expected $code" "$output"
  elif [[ -n $pattern ]] && ! grep -Eq -- "$pattern" <<<"$output"; then
    fail "$name: output does not match /$pattern/" "$output"
  else
    pass "$name"
  fi
}

ref=$images/reference.exr

expect "identical images" 0 "all pixels +256 px +rmse 0 " -- "$ref" "$ref"
expect "identical images, psnr infinite" 0 "psnr inf" -- "$ref" "$ref"
expect "within tolerance" 0 "rmse 0.707[0-9]* <= tolerance 1: pass" -- \
  "$images/close.exr" "$ref" --metric rmse --tol 1
expect "over tolerance exits 1" 1 "rmse 0.707[0-9]* > tolerance 0.1: FAIL" -- \
  "$images/close.exr" "$ref" --metric rmse --tol 0.1
expect "psnr below tolerance exits 1" 1 "psnr .* < tolerance 200: FAIL" -- \
  "$images/close.exr" "$ref" --metric psnr --tol 200
expect "psnr above tolerance" 0 "psnr .* >= tolerance 20: pass" -- \
  "$images/close.exr" "$ref" --metric psnr --tol 20
expect "metric names are case-insensitive" 0 "max .* <= tolerance 1.01: pass" -- \
  "$images/close.exr" "$ref" --metric MAX --tol 1.01

# Only the emitter pixels (columns 0-7 in mask.scene's view) differ.
expect "emitters dominate without a mask" 1 "FAIL" -- \
  "$images/emitters_differ.exr" "$ref" --tol 0.01
expect "mask leaves the emitters out" 0 "non-emitter pixels +128 px +rmse 0 .*" -- \
  "$images/emitters_differ.exr" "$ref" --tol 0.01 --mask-emitters "$images/mask.scene"
expect "masked tolerance applies to the other pixels" 1 "rmse 0.0047[0-9]* > tolerance 0.001" -- \
  "$images/close.exr" "$ref" --tol 0.001 --mask-emitters "$images/mask.scene"

expect "size mismatch exits 3" 3 "images differ in size: 8x8 vs 16x16" -- \
  "$images/small.exr" "$ref"
expect "missing image exits 3" 3 "missing.exr" -- "$scratch/missing.exr" "$ref"
echo "not an image" >"$scratch/garbage.exr"
expect "unreadable image exits 3" 3 "garbage.exr" -- "$scratch/garbage.exr" "$ref"
expect "bad scene for the mask exits 3" 3 "mask-emitters" -- \
  "$ref" "$ref" --mask-emitters "$scratch/missing.scene"
expect "unknown metric exits 2" 2 "" -- "$ref" "$ref" --metric lpips --tol 1
expect "missing reference argument exits 2" 2 "" -- "$ref"

expect "error image" 0 "error image .*errors.png.* to 50" -- \
  "$images/emitters_differ.exr" "$ref" --error-image "$scratch/errors.png"
check "error image is a PNG" cmp -s -n 8 <(printf '\x89PNG\r\n\x1a\n') "$scratch/errors.png"
# 16 rows of image, a separator row and a 6-row legend.
expect "error image has the legend strip" 0 "\(16x23\)" -- \
  "$scratch/errors.png" "$scratch/errors.png"
expect "error image to a missing directory exits 5" 5 "cannot write" -- \
  "$ref" "$ref" --error-image "$scratch/no/such/dir/errors.png"

# SSIM and FLIP judge the tone-mapped images: the emitters (100 against 50) both show as white.
expect "ssim of identical images is 1" 0 "ssim 1 >= tolerance 1: pass" -- \
  "$ref" "$ref" --metric ssim --tol 1
expect "ssim below tolerance exits 1" 1 "ssim 0.9[0-9]* < tolerance 1: FAIL" -- \
  "$images/close.exr" "$ref" --metric ssim --tol 1
expect "ssim within tolerance" 0 "ssim 0.9[0-9]* >= tolerance 0.9: pass" -- \
  "$images/close.exr" "$ref" --metric ssim --tol 0.9
expect "ssim does not see past white" 0 "all pixels .* ssim 1$" -- \
  "$images/emitters_differ.exr" "$ref" --metric ssim
expect "ssim with the mask" 0 "non-emitter pixels +128 px .* ssim 0.9" -- \
  "$images/close.exr" "$ref" --metric ssim --mask-emitters "$images/mask.scene"
expect "flip of identical images is 0" 0 "flip 0 <= tolerance 0: pass" -- \
  "$ref" "$ref" --metric flip --tol 0
expect "flip over tolerance exits 1" 1 "flip [0-9.e-]* > tolerance 0: FAIL" -- \
  "$images/close.exr" "$ref" --metric flip --tol 0
expect "flip error image on the fixed scale" 0 "error image .*flip.png: FLIP, colour scale 0 .* to 1 " -- \
  "$images/close.exr" "$ref" --metric flip --error-image "$scratch/flip.png"
check "flip error image is a PNG" cmp -s -n 8 <(printf '\x89PNG\r\n\x1a\n') "$scratch/flip.png"
expect "ssim error image" 0 "error image .*ssim.png: 1 - SSIM, colour scale 0 " -- \
  "$images/close.exr" "$ref" --metric ssim --error-image "$scratch/ssim.png"
expect "ssim in the json report" 0 "" -- "$images/close.exr" "$ref" --metric ssim --tol 0.5 \
  --json "$scratch/ssim.json"
check "json report holds the ssim" /usr/bin/python3 -c '
import json, sys
report = json.load(open(sys.argv[1]))
assert 0.9 < report["all"]["ssim"] < 1, report
assert report["metric"] == "ssim" and report["pass"] is True, report
' "$scratch/ssim.json"

expect "json report" 0 "" -- "$images/close.exr" "$ref" --tol 1 \
  --mask-emitters "$images/mask.scene" --json "$scratch/report.json"
check "json report parses and holds the metrics" /usr/bin/python3 -c '
import json, sys
report = json.load(open(sys.argv[1]))
assert report["width"] == 16 and report["height"] == 16, report
assert report["all"]["pixels"] == 256 and report["nonEmitter"]["pixels"] == 128, report
assert abs(report["all"]["rmse"] - 0.7071) < 1e-3, report
assert report["metric"] == "rmse" and report["tolerance"] == 1 and report["pass"] is True, report
' "$scratch/report.json"
expect "json report of identical images" 0 "" -- "$ref" "$ref" --json "$scratch/same.json"
check "infinite psnr is null in json" grep -q '"psnr": null' "$scratch/same.json"

finish
