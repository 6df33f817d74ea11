#!/usr/bin/env bash
# The installed package: `cmake --install` into a fresh prefix puts the command line, the
# facade's headers (and no internal ones), the libraries and the CMake package there; the prefix,
# moved elsewhere, renders with the source and build trees out of reach, the same picture as the
# build tree's binary. Usage: installed_test.sh PATH_TO_PENUMBRA SOURCE_DIR BUILD_DIR
source "$(dirname "$0")/../cli/harness.sh" "$@"
build_dir=$3

cmake --install "$build_dir" --prefix "$scratch/prefix" >"$scratch/log" 2>&1
check "cmake --install exits 0" test $? -eq 0
for file in bin/penumbra include/penumbra/penumbra.h include/penumbra/renderer.h \
  include/penumbra/version.h lib/libpenumbra.a lib/cmake/Penumbra/PenumbraConfig.cmake \
  lib/cmake/Penumbra/PenumbraConfigVersion.cmake lib/cmake/Penumbra/PenumbraTargets.cmake \
  share/penumbra/scenes/demo.scene share/doc/penumbra/LICENSE share/doc/penumbra/CITATION.cff; do
  check "installs $file" test -s "$scratch/prefix/$file"
done
check "only the facade's headers" \
  test "$(cd "$scratch/prefix/include" && find . -type f | sort | tr '\n' ' ')" = \
  "./penumbra/error.h ./penumbra/image.h ./penumbra/penumbra.h ./penumbra/renderer.h ./penumbra/scene.h ./penumbra/settings.h ./penumbra/version.h "
# An exported include folder or definition naming the source or build tree would break once
# they are gone.
check "the package names neither the source nor the build tree" \
  bash -c '! grep -rlF -e "$1" -e "$2" "$3"/lib/cmake/Penumbra' _ "$source_dir" "$build_dir" \
  "$scratch/prefix"

mv "$scratch/prefix" "$scratch/moved"
installed=$scratch/moved/bin/penumbra
scene=share/penumbra/scenes/shadow_box.scene
settings=(--size 64x64 --vpls 16)

# unshare: a mount namespace of this user, in which empty folders cover the build and the source
# trees (the build tree first: it may lie inside the source tree, or outside it).
unreachable() {
  unshare --map-root-user --mount bash -c '
    mount -t tmpfs none "$1" && mount -t tmpfs none "$2" || exit 99
    shift 2
    "$@"' _ "$build_dir" "$source_dir" "$@"
}
unreachable test -e "$source_dir/shaders"
check "the trees are out of reach" test $? -eq 1

unreachable "$installed" --version >"$scratch/version" 2>&1
check "--version of the moved install exits 0" test $? -eq 0
check "--version prints the version and the GL renderer" \
  grep -Eq "^penumbra 0\.2\.0$" "$scratch/version"
check "--version names the GL renderer" grep -Eq "^GL renderer: .+OpenGL 4\.[5-9]" "$scratch/version"

unreachable "$installed" render "$scratch/moved/$scene" "${settings[@]}" -o "$scratch/moved.exr" \
  >"$scratch/log" 2>&1
status=$?
if [[ $status -eq 0 ]]; then
  pass "the moved install renders with no source or build tree"
else
  fail "the moved install renders with no source or build tree" "$(cat "$scratch/log")"
fi
# The viewer's hot reload falls back to the embedded shaders, and says so.
unreachable xvfb-run -a -s "-screen 0 640x480x24" "$installed" view "$scratch/moved/$scene" \
  "${settings[@]}" --frames 1 --exit >"$scratch/log" 2>&1
status=$?
if [[ $status -eq 0 ]] &&
  grep -qF "view: shaders embedded in the library at build time (F5 reloads them)" "$scratch/log"; then
  pass "the moved viewer uses its embedded shaders and says so"
else
  fail "the moved viewer uses its embedded shaders and says so" "exit $status: $(cat "$scratch/log")"
fi

# The Python module from the moved prefix, with no pip step: PYTHONPATH is all it takes.
python_dir=$(find "$scratch/moved" -name 'penumbra.cpython-*.so' -printf '%h\n' | head -1)
check "installs the Python module" test -n "$python_dir"
unreachable env PYTHONPATH="$python_dir" /usr/bin/python3 -c '
import sys, penumbra
image = penumbra.render(penumbra.load_scene(sys.argv[1]), size=(64, 64), vpls=16)
assert image.shape == (64, 64, 3) and image.dtype.name == "float32" and image.max() > 0
' "$scratch/moved/$scene" >"$scratch/log" 2>&1
status=$?
if [[ $status -eq 0 ]]; then
  pass "the moved prefix's Python module renders into NumPy"
else
  fail "the moved prefix's Python module renders into NumPy" "exit $status: $(cat "$scratch/log")"
fi

"$penumbra" render "$source_dir/${scene#share/penumbra/}" "${settings[@]}" \
  -o "$scratch/build.exr" 2>"$scratch/log"
"$penumbra" compare "$scratch/moved.exr" "$scratch/build.exr" --metric max --tol 0 \
  >"$scratch/compare" 2>&1
check "its picture is the build tree's, bit for bit" test $? -eq 0

finish
