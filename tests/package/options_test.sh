#!/usr/bin/env bash
# The renderer library alone: with the tests, the viewer, the reference and the Python module
# off, CMake configures with GoogleTest, GLFW, Embree (and TBB) and pybind11 made unfindable,
# Dear ImGui is never looked for, and only the libraries are targets.
# Usage: options_test.sh PATH_TO_PENUMBRA SOURCE_DIR [BUILD_DIR]
source "$(dirname "$0")/../cli/harness.sh" "$@"

unfindable=(-DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON -DCMAKE_DISABLE_FIND_PACKAGE_TBB=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_pybind11=ON)
# The control: the default options need what was made unfindable, so the check below can fail.
cmake -S "$source_dir" -B "$scratch/default" -G Ninja "${unfindable[@]}" >"$scratch/log" 2>&1
check "the default options need them" test $? -ne 0

if cmake -S "$source_dir" -B "$scratch/library" -G Ninja -DPENUMBRA_BUILD_TESTS=OFF \
  -DPENUMBRA_BUILD_VIEWER=OFF -DPENUMBRA_BUILD_REFERENCE=OFF -DPENUMBRA_BUILD_PYTHON=OFF \
  "${unfindable[@]}" \
  >"$scratch/log" 2>&1; then
  pass "the library alone configures without them"
else
  fail "the library alone configures without them" "$(cat "$scratch/log")"
fi
# pkg-config leaves __pkg_config_checked_IMGUI and IMGUI_* in the cache of a build that looked.
check "Dear ImGui is not looked for" bash -c '! grep -q "IMGUI" "$1/CMakeCache.txt"' _ \
  "$scratch/library"
cmake --build "$scratch/library" --target help >"$scratch/targets" 2>&1
check "the facade is a target" grep -q "^penumbra_library:" "$scratch/targets"
for absent in penumbra penumbra_viewer penumbra_reference penumbra_gpu_tests; do
  check "no $absent target" bash -c '! grep -q "^$1:" "$2"' _ "$absent" "$scratch/targets"
done

cmake -S "$source_dir" -B "$scratch/contradiction" -G Ninja -DPENUMBRA_BUILD_REFERENCE=OFF \
  -DPENUMBRA_BUILD_PYTHON=OFF >"$scratch/log" 2>&1
check "tests without the reference are refused with a reason" \
  grep -q "PENUMBRA_BUILD_TESTS needs PENUMBRA_BUILD_REFERENCE" "$scratch/log"
cmake -S "$source_dir" -B "$scratch/python-contradiction" -G Ninja -DPENUMBRA_BUILD_REFERENCE=OFF \
  -DPENUMBRA_BUILD_TESTS=OFF >"$scratch/log" 2>&1
check "the Python module without the reference is refused with a reason" \
  grep -q "PENUMBRA_BUILD_PYTHON needs PENUMBRA_BUILD_REFERENCE" "$scratch/log"

finish
