#!/usr/bin/env bash
# examples/embed, a CMake project of its own, configured and built against a fresh install
# prefix with find_package(Penumbra 0.2 CONFIG REQUIRED), then run under Xvfb for a few frames:
# its window's context renders the scene. Usage: embed_test.sh PATH_TO_PENUMBRA SOURCE_DIR BUILD_DIR
source "$(dirname "$0")/../cli/harness.sh" "$@"
build_dir=$3

cmake --install "$build_dir" --prefix "$scratch/prefix" >"$scratch/log" 2>&1
check "cmake --install exits 0" test $? -eq 0

if cmake -S "$source_dir/examples/embed" -B "$scratch/embed" -G Ninja \
  -DCMAKE_PREFIX_PATH="$scratch/prefix" >"$scratch/log" 2>&1; then
  pass "examples/embed configures against the prefix"
else
  fail "examples/embed configures against the prefix" "$(cat "$scratch/log")"
fi
if cmake --build "$scratch/embed" >"$scratch/log" 2>&1; then
  pass "examples/embed builds"
else
  fail "examples/embed builds" "$(cat "$scratch/log")"
fi

# A version the package does not promise is refused.
mkdir "$scratch/too_new"
cat >"$scratch/too_new/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(too_new LANGUAGES CXX)
find_package(Penumbra 0.3 CONFIG REQUIRED)
CMAKE
cmake -S "$scratch/too_new" -B "$scratch/too_new/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
  >"$scratch/log" 2>&1
check "find_package(Penumbra 0.3) fails against 0.2" test $? -ne 0

# The scene the example builds in memory, and the installed demo scene, 64x64, three frames.
for scene in "" "$scratch/prefix/share/penumbra/scenes/demo.scene"; do
  name=${scene:+demo.scene}
  name=${name:-the scene built in memory}
  xvfb-run -a -s "-screen 0 640x480x24" "$scratch/embed/penumbra_embed" $scene --frames 3 \
    --size 64x64 >"$scratch/run" 2>&1
  status=$?
  if [[ $status -eq 0 ]] && grep -q "penumbra_embed: 3 frames of .*$name at 64x64" "$scratch/run"; then
    pass "penumbra_embed shows 3 frames of $name in its window"
  else
    fail "penumbra_embed shows 3 frames of $name in its window" "exit $status: $(cat "$scratch/run")"
  fi
  # Both scenes are lit: a black picture would mean nothing was rendered.
  check "the picture of $name is lit" /usr/bin/python3 -c '
import re, sys
means = re.search(r"mean radiance (\S+) (\S+) (\S+)", open(sys.argv[1]).read())
sys.exit(0 if means and min(float(v) for v in means.groups()) > 0.001 else 1)' "$scratch/run"
done

finish
